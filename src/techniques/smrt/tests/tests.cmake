# smrt's renders against the reference (in test_render; included by tests/render.cmake).
list(APPEND PENUMBRA_RENDER_TESTS ${CMAKE_CURRENT_LIST_DIR}/render_smrt_test.cpp)
list(APPEND PENUMBRA_RENDER_SANITIZE Smrt.WholeRaysConvergeUnderAParallelPlate)
