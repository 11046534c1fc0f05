# tests of geometry (see tests/CMakeLists.txt)
