# tests of scene (see tests/CMakeLists.txt)
penumbra_add_test(test_scene
  ${CMAKE_CURRENT_SOURCE_DIR}/scene_json_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/scene_shapes_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/scene_gltf_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/scene_compressed_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/scene_files_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/scene_bad_inputs_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/scene_hostile_test.cpp
  LIBS penumbra_scene ZLIB::ZLIB)
