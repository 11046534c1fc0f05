# Writes OUT: a C++ file defining penumbra::gl::embeddedShaders() with the text of each file in
# FILES (absolute paths separated by |), keyed by file name.
string(REPLACE "|" ";" FILES "${FILES}")
set(body "")
foreach(f IN LISTS FILES)
  file(READ "${f}" text)
  get_filename_component(name "${f}" NAME)
  string(APPEND body "    {\"${name}\", R\"penumbra_shader(${text})penumbra_shader\"},\n")
endforeach()
file(WRITE "${OUT}.tmp" "// Generated from shaders/ by shaders/embed.cmake. Do not edit.\n#include <map>\n#include <string>\nnamespace penumbra::gl {\nconst std::map<std::string, std::string>& embeddedShaders() {\n  static const std::map<std::string, std::string> m = {\n${body}  };\n  return m;\n}\n}  // namespace penumbra::gl\n")
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)
