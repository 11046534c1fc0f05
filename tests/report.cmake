# The comparison report: writers without GL; compareTechniques (sweeps, flicker) with
# GL; the HTML page opened in headless Chromium.
penumbra_add_test(test_report ${CMAKE_CURRENT_SOURCE_DIR}/report_test.cpp LIBS penumbra_compare penumbra_cli_options)

penumbra_add_gl_test(test_render_compare ${CMAKE_CURRENT_SOURCE_DIR}/render_compare_test.cpp
  SANITIZE CompareFailure.AFailedTechniqueIsItsRowAndTheOthersGoOn Compare.AFailedReferenceEndsTheRun)

foreach(part sweep default)
  add_test(NAME report_html_chromium_${part} COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/report_html_test.sh $<TARGET_FILE:penumbra>
           ${PROJECT_SOURCE_DIR} ${part})
  set_tests_properties(report_html_chromium_${part} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "gl;browser")
endforeach()
