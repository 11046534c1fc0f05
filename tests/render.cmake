# Rendering tests: need a GL context (EGL surfaceless or OSMesa on Mesa llvmpipe); exit 77
# (skipped) without one. Small images (128-256 px) keep the suite fast.
penumbra_add_gl_test(test_render
  ${CMAKE_CURRENT_SOURCE_DIR}/render_hard_sv_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_pipeline_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_dcs_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_dcs_paths_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_shadow_map_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_pcss_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_msm_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_denoised_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_shipped_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_robustness_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/gl_program_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_timing_test.cpp
  # The sanitizer run's GL tests (label sanitize): each technique once, each exact technique
  # against the reference on one hard case, the error paths that must stay one line.
  SANITIZE
    Table/EveryTechnique.*
    Scenes/HardSvVsRaytrace.*/01_cube_on_plane
    Scenes/DcsVsRaytrace.*/15_two_plates_N16
    Scenes/DcsSemiOpaque.*/glass_layers_N16
    Bases/DcsOverflow.*/base16_plates17
    DcsOverflowRefusal.*
    Scenes/MultiViewVsRaytrace.*/15_two_plates_mvr
    Scenes/MultiViewVsRaytrace.*/stained_glass_vwss
    Scenes/MultiViewVsRaytrace.*/23_analytic_disk_reproject
    Pcss.ParallelPlanesCaseMatchesTheReference
    Vssm.ParallelPlanesCaseAndFusionFailure
    Msm.HardShadowsFromTheLightCentre
    Enclosure.SeparatesOnlyWhatEveryPathCrosses
    MsmSoft.ParallelPlanesCase
    Evsm.ParallelPlanesAndBleedingAgainstVssm
    RaytraceDenoised.StillSceneConvergesToTheSameSamples
    Pipeline.NonFiniteImagesAreAnErrorNamingTheTechnique
    Pipeline.GlossyShadingIsTheSharedBrdfOnGpuAndCpu
    Robustness.FarFromTheOriginEqualsTheUntranslatedScene
    MultiView.VwssWithoutPointsIsAnError
    MultiView.DepthPassWithoutFragmentsIsAnError
    ShaderLoader.*
  LLVMPIPE
    Pipeline.EglAndOSMesaGiveTheSameImage
  SLOW
    DcsRasterPath.EndPlanesCutTheFillNotTheResult
    HardCase34.ViewRaysThroughVertexLinesCountEveryVolume
    MultiView.VwssSplitsPointsThatExceedOneStorageBlock)

# The CLI: exit codes and one-line errors for bad input (tests/cli_test.sh), in two parts: the
# inputs refused before any GL work (no GL context needed) and the rendering cases.
add_test(NAME cli_inputs COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/cli_test.sh $<TARGET_FILE:penumbra> ${PROJECT_SOURCE_DIR} inputs)
set_tests_properties(cli_inputs PROPERTIES LABELS cpu)
add_test(NAME cli_render COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/cli_test.sh $<TARGET_FILE:penumbra> ${PROJECT_SOURCE_DIR} render)
set_tests_properties(cli_render PROPERTIES SKIP_RETURN_CODE 77 LABELS "gl;sanitize")

# The docs' tables generated from the code (README's techniques, docs/cli.md's parameters) equal
# it, README links every page of docs/ (tests/generated_tables_test.sh); every citation resolves
# in docs/references.md and no issue number is left (tests/references_test.sh). No GL needed.
add_test(NAME generated_tables COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/generated_tables_test.sh $<TARGET_FILE:penumbra>
         ${PROJECT_SOURCE_DIR})
add_test(NAME references COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/references_test.sh ${PROJECT_SOURCE_DIR})
# No flag named outside src/cli (tests/flags_test.sh).
add_test(NAME flags_only_in_cli COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/flags_test.sh ${PROJECT_SOURCE_DIR})
set_tests_properties(generated_tables references flags_only_in_cli PROPERTIES LABELS cpu)

# Technique parameters: declarations, dcs through --param, the shared key/value reader. No GL.
penumbra_add_test(test_technique_params ${CMAKE_CURRENT_SOURCE_DIR}/technique_params_test.cpp LIBS penumbra_techniques)

# The 4MSM reconstruction (shaders/shared.h penumbraMsm4), GL-free.
penumbra_add_test(test_moments ${CMAKE_CURRENT_SOURCE_DIR}/moments_test.cpp LIBS penumbra_sampling)

# DCS counter packing: no GL needed.
penumbra_add_test(test_dcs_packing ${CMAKE_CURRENT_SOURCE_DIR}/dcs_packing_test.cpp LIBS penumbra_techniques)

# DCS semi-opaque unit coding: no GL needed.
penumbra_add_test(test_dcs_opacity ${CMAKE_CURRENT_SOURCE_DIR}/dcs_opacity_test.cpp LIBS penumbra_techniques)

# DCS edge LUT files: no GL needed.
penumbra_add_test(test_dcs_edge_lut ${CMAKE_CURRENT_SOURCE_DIR}/dcs_edge_lut_test.cpp LIBS penumbra_techniques)

# Resource hygiene: repeated renders leak no GL objects or memory; GL limits and out-of-memory
# are one-line errors.
penumbra_add_gl_test(test_render_resources ${CMAKE_CURRENT_SOURCE_DIR}/render_resources_test.cpp
  SANITIZE RenderResources.LimitsAreErrorsNotGlErrors)

# The shadow-volume count's exact face decisions and covers (shared.h, volume_cover.h). No GL.
penumbra_add_test(test_shadow_volume_count ${CMAKE_CURRENT_SOURCE_DIR}/shadow_volume_count_test.cpp LIBS penumbra_techniques)
