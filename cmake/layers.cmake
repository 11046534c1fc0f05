# The layers of penumbra and which may use which (docs/architecture.md). Held by the build twice:
#
#  * include roots: a library's headers are reachable only through its own root,
#    <build>/include/<target>/<folder> (a link to the source folder), which it publishes PUBLIC.
#    A target sees a header only if it links (directly or through PUBLIC links) the library
#    that owns it, so a lower layer including an upper layer's header fails to compile
#    (tests/layering.cmake proves it);
#  * link lists: penumbra_check_layers() refuses, at configure time, a penumbra_* library that
#    links a penumbra_* library its row below does not allow.
#
# target                     may link (directly)
set(PENUMBRA_LAYERS
  "penumbra_shared:"
  "penumbra_core:"
  "penumbra_geometry:penumbra_core"
  "penumbra_scene:penumbra_shared,penumbra_core,penumbra_geometry"
  "penumbra_sampling:penumbra_shared,penumbra_core,penumbra_scene"
  "penumbra_shading:penumbra_core,penumbra_sampling"
  "penumbra_shaders:"
  "penumbra_gl:penumbra_core,penumbra_shaders"
  "penumbra_pipeline:penumbra_core,penumbra_geometry,penumbra_scene,penumbra_sampling,penumbra_shading,penumbra_gl"
  "penumbra_reference:penumbra_core,penumbra_scene,penumbra_sampling,penumbra_shading"
  "penumbra_techniques:penumbra_core,penumbra_geometry,penumbra_scene,penumbra_sampling,penumbra_gl,penumbra_pipeline,penumbra_reference"
  "penumbra_compare:penumbra_core,penumbra_scene,penumbra_sampling,penumbra_gl,penumbra_pipeline"
  "penumbra_study:penumbra_core,penumbra_scene,penumbra_sampling,penumbra_gl,penumbra_pipeline,penumbra_techniques,penumbra_compare"
  "penumbra_cli_options:penumbra_sampling,penumbra_gl,penumbra_pipeline,penumbra_compare"
  "penumbra_bench_studies:penumbra_core,penumbra_scene,penumbra_sampling,penumbra_gl,penumbra_pipeline,penumbra_techniques,penumbra_compare,penumbra_study"
)

# penumbra_include_root(target folder source_dir): `#include "<folder>/x.h"` finds source_dir/x.h
# for `target` and whatever links it, and for nothing else.
function(penumbra_include_root target folder source_dir)
  set(root ${CMAKE_BINARY_DIR}/include/${target})
  get_filename_component(parent ${root}/${folder} DIRECTORY)
  file(MAKE_DIRECTORY ${parent})
  if(NOT IS_SYMLINK ${root}/${folder})
    file(CREATE_LINK ${source_dir} ${root}/${folder} SYMBOLIC)
  endif()
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_include_directories(${target} INTERFACE ${root})
  else()
    target_include_directories(${target} PUBLIC ${root})
  endif()
endfunction()

# Called once every target exists (top-level CMakeLists.txt).
function(penumbra_check_layers)
  foreach(row IN LISTS PENUMBRA_LAYERS)
    string(REPLACE ":" ";" parts "${row}")
    list(GET parts 0 target)
    list(LENGTH parts n)
    set(allowed "")
    if(n GREATER 1)
      list(GET parts 1 allowed)
      string(REPLACE "," ";" allowed "${allowed}")
    endif()
    if(NOT TARGET ${target})
      message(FATAL_ERROR "cmake/layers.cmake: layer ${target} has no target")
    endif()
    get_target_property(links ${target} LINK_LIBRARIES)
    get_target_property(interface ${target} INTERFACE_LINK_LIBRARIES)
    foreach(lib IN LISTS links interface)
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" lib "${lib}")
      if(lib MATCHES "^penumbra_" AND NOT lib STREQUAL "penumbra_warnings" AND NOT lib IN_LIST allowed)
        message(FATAL_ERROR "cmake/layers.cmake: ${target} links ${lib}, a layer it may not use "
                            "(allowed: ${allowed})")
      endif()
    endforeach()
  endforeach()
endfunction()
