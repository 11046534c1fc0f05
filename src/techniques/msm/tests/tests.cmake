# msm's tests (included by tests/render.cmake): the 4MSM reconstruction (common/shadow_map/shaders/moments.h penumbraMsm4),
# GL-free; msm and msm-soft against the reference (in test_render).
penumbra_add_test(test_moments ${CMAKE_CURRENT_LIST_DIR}/moments_test.cpp LIBS penumbra_techniques)
list(APPEND PENUMBRA_RENDER_TESTS ${CMAKE_CURRENT_LIST_DIR}/render_msm_test.cpp)
list(APPEND PENUMBRA_RENDER_SANITIZE Msm.HardShadowsFromTheLightCentre MsmSoft.ParallelPlanesCase)
