# tests of raytrace (see tests/CMakeLists.txt)
