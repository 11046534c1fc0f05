# tests of core (see tests/CMakeLists.txt). OpenEXR and libpng are linked directly so the tests
# can craft files (multi-part, deep, odd PNG layouts) that penumbra itself never writes.
penumbra_add_test(test_core
  ${CMAKE_CURRENT_SOURCE_DIR}/core_image_io_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/core_png_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/core_metrics_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/core_flip_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/core_timer_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/core_error_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/core_files_test.cpp
  LIBS penumbra_core OpenEXR::OpenEXR PNG::PNG)
