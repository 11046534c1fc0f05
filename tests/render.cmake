# tests of render (see tests/CMakeLists.txt)
