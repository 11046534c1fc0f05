# Hard case 24: determinism across llvmpipe thread counts, repeated runs and the EGL/OSMesa
# backends (tests/determinism_test.sh; separate processes, since LP_NUM_THREADS is read when
# llvmpipe's screen is created). Exits 77 (skipped) only without a GL context.
add_executable(exr_diff ${CMAKE_CURRENT_SOURCE_DIR}/exr_diff.cpp)
target_link_libraries(exr_diff PRIVATE penumbra_core penumbra_warnings)
# One test per group of scenes (tests/determinism_test.sh GROUP), each well under 30 s.
foreach(group cube-volumes cube-maps cube-filters cube-moments plates-volumes plates-maps two-plates
              sphere-grid-dcs sphere-grid)
  add_test(NAME determinism_${group} COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/determinism_test.sh $<TARGET_FILE:penumbra>
           $<TARGET_FILE:exr_diff> ${PROJECT_SOURCE_DIR} ${group})
  set_tests_properties(determinism_${group} PROPERTIES SKIP_RETURN_CODE 77 LABELS "gl;llvmpipe")
endforeach()
set_tests_properties(determinism_sphere-grid-dcs PROPERTIES LABELS "gl;llvmpipe;slow")
