# The comparison report (issue 7): writers without GL; compareTechniques (sweeps, flicker) with
# GL; the HTML page opened in headless Chromium.
penumbra_add_test(test_report ${CMAKE_CURRENT_SOURCE_DIR}/report_test.cpp LIBS penumbra_render)

add_executable(test_render_compare ${CMAKE_CURRENT_SOURCE_DIR}/gl_test_main.cpp
               ${CMAKE_CURRENT_SOURCE_DIR}/render_compare_test.cpp)
target_link_libraries(test_render_compare PRIVATE penumbra_render penumbra_scene GTest::gtest penumbra_warnings)
target_compile_definitions(test_render_compare PRIVATE PENUMBRA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
gtest_discover_tests(test_render_compare PROPERTIES SKIP_RETURN_CODE 77 DISCOVERY_TIMEOUT 60
                     ENVIRONMENT "LP_NUM_THREADS=2")

add_test(NAME report_html_chromium COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/report_html_test.sh $<TARGET_FILE:penumbra>
         ${PROJECT_SOURCE_DIR})
set_tests_properties(report_html_chromium PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)
