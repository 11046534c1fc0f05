# tests of raytrace and shading (see tests/CMakeLists.txt)
# Light-sample sets (GL-free) and the Embree reference (GL-free).
penumbra_add_test(test_sampling ${CMAKE_CURRENT_SOURCE_DIR}/sampling_light_samples.cpp
                  LIBS penumbra_sampling penumbra_cli_options)
penumbra_add_test(test_raytrace ${CMAKE_CURRENT_SOURCE_DIR}/raytrace_embree.cpp
                  ${CMAKE_CURRENT_SOURCE_DIR}/raytrace_analytic.cpp
                  ${CMAKE_CURRENT_SOURCE_DIR}/raytrace_converged_test.cpp
                  LIBS penumbra_reference)
# The LTC GGX table, its fit and the shader's polygon integral on the CPU (GL-free).
penumbra_add_test(test_shading ${CMAKE_CURRENT_SOURCE_DIR}/shading_ltc_test.cpp
                  ${CMAKE_CURRENT_SOURCE_DIR}/shading_prefilter_test.cpp LIBS penumbra_shading)
