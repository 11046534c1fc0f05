# tests of scene (see tests/CMakeLists.txt)
