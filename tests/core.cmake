# tests of core (see tests/CMakeLists.txt)
