// The text a shader stage is compiled from: "#version 450 core", the defines, src/shared/shared.h (the ground floor),
// then the file with each `#include "name"` replaced by the named file (nested includes too,
// each file once, headers wherever included). `#line` directives number the lines of file k
// from k * 100000 + 1, so the GL's error log can name the file and line of an error
// (nameLogLocations).
#pragma once

#include <string>
#include <vector>

namespace penumbra::gl {

struct ShaderText {
  std::string text;
  std::vector<std::string> files;  // by number: 0 the stage's file, 1 shared.h (the ground floor), then includes
};

ShaderText assembleShader(const std::string& file, const std::vector<std::string>& defines);

// A compile log with each "S:L(C)" (Mesa) or "S(L)" (NVIDIA) location written as the file and
// line that L encodes ("common_dcs.glsl:12(3)"), on one line.
std::string nameLogLocations(const std::string& log, const std::vector<std::string>& files);

}  // namespace penumbra::gl
