# dcs's tests (included by tests/render.cmake): the GL-free units, and its renders against the
# reference (in test_render).
# Counter packing, the semi-opaque unit coding, edge LUT files: no GL needed.
penumbra_add_test(test_dcs_packing ${CMAKE_CURRENT_LIST_DIR}/dcs_packing_test.cpp LIBS penumbra_techniques)
penumbra_add_test(test_dcs_opacity ${CMAKE_CURRENT_LIST_DIR}/dcs_opacity_test.cpp LIBS penumbra_techniques)
penumbra_add_test(test_dcs_edge_lut ${CMAKE_CURRENT_LIST_DIR}/dcs_edge_lut_test.cpp LIBS penumbra_techniques)
list(APPEND PENUMBRA_RENDER_TESTS ${CMAKE_CURRENT_LIST_DIR}/render_dcs_test.cpp ${CMAKE_CURRENT_LIST_DIR}/render_dcs_paths_test.cpp)
list(APPEND PENUMBRA_RENDER_SANITIZE Scenes/DcsVsRaytrace.*/15_two_plates_N16 Scenes/DcsSemiOpaque.*/glass_layers_N16
     Bases/DcsOverflow.*/base16_plates17 DcsOverflowRefusal.*)
list(APPEND PENUMBRA_RENDER_SLOW DcsRasterPath.EndPlanesCutTheFillNotTheResult Samples/HardCase34.ViewRaysThroughVertexLinesCountEveryVolume/*)
