# raytrace-denoised's renders (in test_render; included by tests/render.cmake).
list(APPEND PENUMBRA_RENDER_TESTS ${CMAKE_CURRENT_LIST_DIR}/render_denoised_test.cpp)
list(APPEND PENUMBRA_RENDER_SANITIZE RaytraceDenoised.StillSceneConvergesToTheSameSamples HardCase35.DenoisedKeepsAClosedBoxDark)
