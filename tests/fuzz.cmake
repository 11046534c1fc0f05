# Fuzzing of the scene loader (tests/fuzz/, hard-cases.md "Bad inputs: expected behaviour").
# Always built: test_fuzz_replay replays the seed corpus and every regression input through the
# loader with the fuzz targets' own checks (tests/fuzz/fuzz_harness.cpp).
penumbra_add_test(test_fuzz_replay
  ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/replay_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/fuzz_harness.cpp
  LIBS penumbra_scene)
target_include_directories(test_fuzz_replay PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/fuzz)

# The libFuzzer targets themselves: clang only, in a build tree of their own (tests/fuzz/run.sh
# configures build-fuzz/ with them). OFF by default; CI may run them, nothing else needs them.
option(PENUMBRA_FUZZ "Build the libFuzzer targets of the scene loader (clang, build-fuzz/)" OFF)
if(PENUMBRA_FUZZ)
  add_subdirectory(${CMAKE_CURRENT_SOURCE_DIR}/fuzz ${CMAKE_CURRENT_BINARY_DIR}/fuzz)
endif()
