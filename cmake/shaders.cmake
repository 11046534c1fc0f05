# Shaders are files (prefix_name.stage) in the folder of the code that runs them: the pipeline's
# in shaders/, a technique's in src/techniques/<name>/shaders/. All are embedded into the binary
# at build time, keyed by file name, so a name is unique across the tree (checked here); a
# stage's `#include "file"` finds any of them by that name (src/gl/shader_source.cpp).

# penumbra_shader_folder(dir): the shader files of dir (stages, *.glsl, C++/GLSL headers *.h)
# join the embedded set.
function(penumbra_shader_folder dir)
  file(GLOB files CONFIGURE_DEPENDS ${dir}/*.vert ${dir}/*.frag ${dir}/*.geom ${dir}/*.comp ${dir}/*.glsl ${dir}/*.h)
  if(NOT files)
    message(FATAL_ERROR "${dir}: a shader folder without shaders")
  endif()
  set_property(GLOBAL APPEND PROPERTY PENUMBRA_SHADER_FILES ${files})
endfunction()

# penumbra_embed_shaders(): once every folder has declared its shaders (top-level
# CMakeLists.txt), the library penumbra_shaders holding their text (shaders/embed.cmake).
function(penumbra_embed_shaders)
  get_property(files GLOBAL PROPERTY PENUMBRA_SHADER_FILES)
  set(names "")
  foreach(f IN LISTS files)
    get_filename_component(name ${f} NAME)
    if(name IN_LIST names)
      list(FILTER files INCLUDE REGEX "/${name}$")
      message(FATAL_ERROR "shader file name ${name} used twice (shaders are embedded by name): ${files}")
    endif()
    list(APPEND names ${name})
  endforeach()
  set(out ${CMAKE_BINARY_DIR}/shaders/embedded_shaders.cpp)
  string(REPLACE ";" "|" files_arg "${files}")
  add_custom_command(OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} "-DFILES=${files_arg}" -DOUT=${out} -P ${PROJECT_SOURCE_DIR}/shaders/embed.cmake
    DEPENDS ${files} ${PROJECT_SOURCE_DIR}/shaders/embed.cmake
    COMMENT "Embedding shaders" VERBATIM)
  add_library(penumbra_shaders STATIC ${out})
endfunction()
