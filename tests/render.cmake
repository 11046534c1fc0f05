# Rendering tests: need a GL context (EGL surfaceless or OSMesa on Mesa llvmpipe); exit 77
# (skipped) without one. Small images (128-256 px) keep the suite fast.
# The renders of the pipeline itself and of no one technique; each technique folder's
# tests/tests.cmake adds its own to these lists (and may declare GL-free executables).
set(PENUMBRA_RENDER_TESTS
  ${CMAKE_CURRENT_SOURCE_DIR}/render_pipeline_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_shipped_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_assets_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_robustness_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/gl_program_test.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/render_timing_test.cpp)
# The sanitizer run's GL tests (label sanitize): each technique once, each exact technique
# against the reference on one hard case, the error paths that must stay one line.
set(PENUMBRA_RENDER_SANITIZE
  Table/EveryTechnique.*
  Pipeline.NonFiniteImagesAreAnErrorNamingTheTechnique
  Pipeline.GlossyShadingIsTheSharedBrdfOnGpuAndCpu
  Robustness.FarFromTheOriginEqualsTheUntranslatedScene
  Assets.AlphaTestedCardIsItsOpaqueCells
  ShaderLoader.*)
set(PENUMBRA_RENDER_SLOW "")
foreach(folder IN LISTS PENUMBRA_TECHNIQUE_BASES PENUMBRA_TECHNIQUE_FOLDERS)
  include(${PROJECT_SOURCE_DIR}/src/techniques/${folder}/tests/tests.cmake OPTIONAL)
endforeach()
penumbra_add_gl_test(test_render ${PENUMBRA_RENDER_TESTS}
  SANITIZE ${PENUMBRA_RENDER_SANITIZE}
  LLVMPIPE Pipeline.EglAndOSMesaGiveTheSameImage
  SLOW ${PENUMBRA_RENDER_SLOW})

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

# Resource hygiene: repeated renders leak no GL objects or memory; GL limits and out-of-memory
# are one-line errors.
penumbra_add_gl_test(test_render_resources ${CMAKE_CURRENT_SOURCE_DIR}/render_resources_test.cpp
  SANITIZE RenderResources.LimitsAreErrorsNotGlErrors)
