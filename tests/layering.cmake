# The build refuses a wrong include direction (cmake/layers.cmake). Each probe is a one-line
# source compiled as a target that links one layer: `refused` probes include a header of a layer
# above it and must fail with "not found" for that header; `allowed` probes include a header
# below it and must compile (so a refusal is the include root's doing, not a broken probe).
# The probes are not part of `all`; each test builds its own with `cmake --build`.
function(penumbra_layer_probe kind layer header)
  string(MAKE_C_IDENTIFIER "${kind}_${layer}_${header}" name)
  set(source ${CMAKE_CURRENT_BINARY_DIR}/layering/${name}.cpp)
  file(CONFIGURE OUTPUT ${source} CONTENT "#include \"${header}\"\n")
  add_library(${name} OBJECT EXCLUDE_FROM_ALL ${source})
  target_link_libraries(${name} PRIVATE ${layer})
  add_test(NAME layering_${name} COMMAND ${CMAKE_COMMAND} --build ${CMAKE_BINARY_DIR} --target ${name})
  # One build at a time in this tree (ninja's log is not shared safely between runs).
  set_tests_properties(layering_${name} PROPERTIES RESOURCE_LOCK penumbra_build_tree LABELS cpu)
  if(kind STREQUAL "refused")
    string(REPLACE "." "\\." pattern "${header}")
    set_tests_properties(layering_${name} PROPERTIES
                         PASS_REGULAR_EXPRESSION "${pattern}'?:? (No such file or directory|file not found)"
                         FAIL_REGULAR_EXPRESSION "Linking|layers\\.cmake")
  endif()
endfunction()

penumbra_layer_probe(refused penumbra_core geometry/mesh.h)
penumbra_layer_probe(refused penumbra_geometry scene/scene.h)
penumbra_layer_probe(refused penumbra_scene sampling/light_samples.h)
penumbra_layer_probe(refused penumbra_sampling gl/objects.h)
penumbra_layer_probe(refused penumbra_gl pipeline/renderer.h)
penumbra_layer_probe(refused penumbra_reference pipeline/technique.h)
penumbra_layer_probe(refused penumbra_pipeline techniques/registry.h)
penumbra_layer_probe(refused penumbra_pipeline compare/compare.h)
penumbra_layer_probe(refused penumbra_techniques compare/compare.h)
penumbra_layer_probe(refused penumbra_compare techniques/registry.h)
penumbra_layer_probe(refused penumbra_compare cli/options.h)
penumbra_layer_probe(refused penumbra_techniques study/plan.h)
# A technique's binding header (beside its shaders) is its own: neither the pipeline nor compare
# sees it, by its path or by its bare name (no layer exports a shader folder wholesale), and the
# ground floor is the bottom: it sees no layer.
penumbra_layer_probe(refused penumbra_pipeline techniques/dcs/shaders/dcs_bindings.h)
penumbra_layer_probe(refused penumbra_pipeline dcs_bindings.h)
penumbra_layer_probe(refused penumbra_compare techniques/common/shadow_map/shaders/shadow_map_bindings.h)
penumbra_layer_probe(refused penumbra_compare shadow_map_bindings.h)
penumbra_layer_probe(refused penumbra_pipeline shared.h)
penumbra_layer_probe(refused penumbra_shared core/error.h)
penumbra_layer_probe(allowed penumbra_pipeline scene/gbuffer.h)
penumbra_layer_probe(allowed penumbra_scene shared/shared.h)
penumbra_layer_probe(allowed penumbra_techniques techniques/dcs/shaders/dcs_bindings.h)
penumbra_layer_probe(allowed penumbra_techniques pipeline/renderer.h)
penumbra_layer_probe(allowed penumbra_compare pipeline/technique.h)
