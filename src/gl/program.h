// The shader-program builder: a gl::Program (an RAII object of gl/objects.h) from shader files.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"

namespace penumbra::gl {

// A program from shader files, named by file name: the pipeline's under shaders/, a
// technique's under its folder's shaders/ (all embedded at build time; read from the folders
// $PENUMBRA_SHADER_DIR lists, ':'-separated, instead when set, for iterating). Each source gets "#version 450 core",
// the given defines ("NAME" or "NAME VALUE"), src/shared/shared.h and its #include "file" lines
// resolved. Compile/link errors throw penumbra::Error naming the shader file.
class Program : public Object<Kind::Program> {
 public:
  Program() = default;
  Program(const std::vector<std::string>& files, const std::vector<std::string>& defines = {});
  void use() const;
  GLint location(const char* name) const;
  void set(const char* name, int v) const;
  void set(const char* name, unsigned v) const;
  void set(const char* name, float v) const;
  void set(const char* name, const glm::vec2& v) const;
  void set(const char* name, const glm::ivec2& v) const;
  void set(const char* name, const glm::vec3& v) const;
  void set(const char* name, const glm::vec4& v) const;
  void set(const char* name, const glm::mat4& v) const;
};

// Source text of a shader file (embedded, or the first of $PENUMBRA_SHADER_DIR's folders holding it).
std::string shaderSource(const std::string& file);

}  // namespace penumbra::gl
