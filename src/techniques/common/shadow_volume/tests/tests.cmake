# The shadow-volume count's exact face decisions and covers (shaders/volume_count.h, volume_cover.h). No GL.
penumbra_add_test(test_shadow_volume_count ${CMAKE_CURRENT_LIST_DIR}/shadow_volume_count_test.cpp LIBS penumbra_techniques)
