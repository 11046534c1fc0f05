# The shadow-map framework's tests (in test_render; included by tests/render.cmake): the
# multi-view techniques (mvr, vwss, reproject) against the reference, the separated-light
# culling, the single-map family on the analytic cases.
list(APPEND PENUMBRA_RENDER_TESTS ${CMAKE_CURRENT_LIST_DIR}/render_shadow_map_test.cpp
     ${CMAKE_CURRENT_LIST_DIR}/render_single_view_test.cpp)
list(APPEND PENUMBRA_RENDER_SANITIZE Scenes/MultiViewVsRaytrace.*/15_two_plates_mvr Scenes/MultiViewVsRaytrace.*/stained_glass_vwss
     Scenes/MultiViewVsRaytrace.*/23_analytic_disk_reproject Enclosure.SeparatesOnlyWhatEveryPathCrosses
     MultiView.VwssWithoutPointsIsAnError MultiView.DepthPassWithoutFragmentsIsAnError)
list(APPEND PENUMBRA_RENDER_SLOW MultiView.VwssSplitsPointsThatExceedOneStorageBlock)
