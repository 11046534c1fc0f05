# Rendering tests: need a GL context (EGL surfaceless or OSMesa on Mesa llvmpipe); exit 77
# (skipped) without one. Small images (128-256 px) keep the suite fast.
add_executable(test_render ${CMAKE_CURRENT_SOURCE_DIR}/gl_test_main.cpp
               ${CMAKE_CURRENT_SOURCE_DIR}/render_hard_sv_test.cpp
               ${CMAKE_CURRENT_SOURCE_DIR}/render_pipeline_test.cpp
               ${CMAKE_CURRENT_SOURCE_DIR}/render_dcs_test.cpp
               ${CMAKE_CURRENT_SOURCE_DIR}/render_shadow_map_test.cpp
               ${CMAKE_CURRENT_SOURCE_DIR}/render_pcss_test.cpp)
target_link_libraries(test_render PRIVATE penumbra_render penumbra_scene GTest::gtest penumbra_warnings)
target_compile_definitions(test_render PRIVATE PENUMBRA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
gtest_discover_tests(test_render PROPERTIES SKIP_RETURN_CODE 77 DISCOVERY_TIMEOUT 60
                     ENVIRONMENT "LP_NUM_THREADS=2")

# The CLI: exit codes and one-line errors for bad input (tests/cli_test.sh).
add_test(NAME cli_exit_codes COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/cli_test.sh $<TARGET_FILE:penumbra>
         ${PROJECT_SOURCE_DIR})
set_tests_properties(cli_exit_codes PROPERTIES SKIP_RETURN_CODE 77)

# DCS counter packing: no GL needed.
penumbra_add_test(test_dcs_packing ${CMAKE_CURRENT_SOURCE_DIR}/dcs_packing_test.cpp LIBS penumbra_render)

# DCS semi-opaque unit coding: no GL needed.
penumbra_add_test(test_dcs_opacity ${CMAKE_CURRENT_SOURCE_DIR}/dcs_opacity_test.cpp LIBS penumbra_render)

# DCS edge LUT files: no GL needed.
penumbra_add_test(test_dcs_edge_lut ${CMAKE_CURRENT_SOURCE_DIR}/dcs_edge_lut_test.cpp LIBS penumbra_render)

# Resource hygiene: repeated renders leak no GL objects or memory; GL limits and out-of-memory
# are one-line errors (issue 7).
add_executable(test_render_resources ${CMAKE_CURRENT_SOURCE_DIR}/gl_test_main.cpp
               ${CMAKE_CURRENT_SOURCE_DIR}/render_resources_test.cpp)
target_link_libraries(test_render_resources PRIVATE penumbra_render penumbra_scene GTest::gtest penumbra_warnings)
target_compile_definitions(test_render_resources PRIVATE PENUMBRA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
gtest_discover_tests(test_render_resources PROPERTIES SKIP_RETURN_CODE 77 DISCOVERY_TIMEOUT 60
                     ENVIRONMENT "LP_NUM_THREADS=2")
