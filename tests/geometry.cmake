# tests of geometry (see tests/CMakeLists.txt)
# OpenMesh is the product's half-edge mesh (geometry_half_edge_test.cpp) and an oracle for
# reading valid files (geometry_io_test.cpp).
penumbra_add_test(test_geometry
  ${CMAKE_CURRENT_SOURCE_DIR}/geometry_topology_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/geometry_io_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/geometry_half_edge_test.cpp
  LIBS penumbra_geometry OpenMeshCore)
