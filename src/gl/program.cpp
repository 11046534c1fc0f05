// The shader-program builder (gl/program.h): shader files, defines, #include resolution,
// compile and link errors.
#include "gl/program.h"

#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "gl/shader_source.h"

namespace penumbra::gl {

// Generated at build time from every shader folder (cmake/shaders.cmake).
const std::map<std::string, std::string>& embeddedShaders();

std::string shaderSource(const std::string& file) {
  // Set and empty is a mistake (`PENUMBRA_SHADER_DIR= penumbra ...`), not the root folder.
  if (const char* dirs = std::getenv("PENUMBRA_SHADER_DIR")) {
    if (!*dirs)
      throw Error("PENUMBRA_SHADER_DIR", "is set but empty: unset it for the built-in shaders, or name a folder");
    // Folders separated by ':', searched in order (shaders live beside the code that runs them).
    std::stringstream list(dirs);
    for (std::string dir; std::getline(list, dir, ':');) {
      if (dir.empty()) continue;
      std::ifstream in(dir + "/" + file);
      if (!in) continue;
      std::stringstream ss;
      ss << in.rdbuf();
      return ss.str();
    }
    throw Error(file, std::string("no such shader in PENUMBRA_SHADER_DIR (") + dirs + ")");
  }
  auto& m = embeddedShaders();
  auto it = m.find(file);
  if (it == m.end()) throw Error(file, "no such embedded shader");
  return it->second;
}

namespace {

GLenum stageOf(const std::string& file) {
  auto ext = file.substr(file.rfind('.') + 1);
  if (ext == "vert") return GL_VERTEX_SHADER;
  if (ext == "frag") return GL_FRAGMENT_SHADER;
  if (ext == "geom") return GL_GEOMETRY_SHADER;
  if (ext == "comp") return GL_COMPUTE_SHADER;
  throw Error(file, "unknown shader stage (.vert .frag .geom .comp)");
}

// shared/shared.h, "shader storage bindings": in a graphics program that writes a storage block, only
// one stage may declare storage blocks (Mesa 22.3 marks the writing stage's block read-only
// otherwise, and zink then skips the waits and barriers its writes need). Read from the
// stages' text, since the GL reports neither unused declarations (which trigger it too) nor
// readonly: conservative across #if branches, which is what keeps every stage's layout plain.
void checkStorageBlockStages(const std::vector<std::string>& files, const std::vector<std::string>& sources) {
  static const std::regex decl(R"(^\s*layout\s*\([^)]*\)\s*((?:\w+\s+)*)buffer\s+(\w+))");
  int declaring = 0;
  std::string writer;
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (stageOf(files[i]) == GL_COMPUTE_SHADER) return;  // a single stage
    std::istringstream in(sources[i]);
    bool any = false;
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      if (!std::regex_search(line, m, decl)) continue;
      any = true;
      if (m[1].str().find("readonly") == std::string::npos) writer = m[2].str() + " (" + files[i] + ")";
    }
    declaring += any ? 1 : 0;
  }
  if (!writer.empty() && declaring > 1)
    throw Error(files.front(), "storage block " + writer + " is writable while " + std::to_string(declaring) +
                                   " stages declare storage blocks (shared/shared.h, storage bindings)");
}

}  // namespace

Program::Program(const std::vector<std::string>& files, const std::vector<std::string>& defines) {
  GLuint prog = glCreateProgram();
  static_cast<Object&>(*this) = Object(prog);
  // Compiled stages are deleted however this constructor leaves (a later stage may throw).
  struct Stages {
    std::vector<GLuint> ids;
    ~Stages() {
      for (GLuint sh : ids) detail::deleteObject(Kind::Shader, sh);
    }
  } stages;
  std::vector<GLuint>& shaders = stages.ids;
  std::vector<std::string> sources;
  for (auto& file : files) {
    const ShaderText text = assembleShader(file, defines);
    const std::string& src = text.text;
    sources.push_back(src);
    GLuint sh = glCreateShader(stageOf(file));
    detail::objectCreated(Kind::Shader);
    const char* p = src.c_str();
    glShaderSource(sh, 1, &p, nullptr);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[4096];
      glGetShaderInfoLog(sh, sizeof log, nullptr, log);
      detail::deleteObject(Kind::Shader, sh);
      throw Error(file, "compile error: " + nameLogLocations(log, text.files));
    }
    glAttachShader(prog, sh);
    shaders.push_back(sh);
  }
  glLinkProgram(prog);
  for (GLuint sh : shaders) detail::deleteObject(Kind::Shader, sh);
  shaders.clear();
  GLint ok = 0;
  glGetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096];
    glGetProgramInfoLog(prog, sizeof log, nullptr, log);
    std::string msg(log);
    for (auto& c : msg)
      if (c == '\n') c = ' ';
    throw Error(files.front(), "link error: " + msg);
  }
  checkStorageBlockStages(files, sources);
}

void Program::use() const { glUseProgram(id()); }
GLint Program::location(const char* name) const { return glGetUniformLocation(id(), name); }
void Program::set(const char* n, int v) const { glProgramUniform1i(id(), location(n), v); }
void Program::set(const char* n, unsigned v) const { glProgramUniform1ui(id(), location(n), v); }
void Program::set(const char* n, float v) const { glProgramUniform1f(id(), location(n), v); }
void Program::set(const char* n, const glm::vec2& v) const { glProgramUniform2f(id(), location(n), v.x, v.y); }
void Program::set(const char* n, const glm::ivec2& v) const { glProgramUniform2i(id(), location(n), v.x, v.y); }
void Program::set(const char* n, const glm::vec3& v) const {
  glProgramUniform3fv(id(), location(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, const glm::vec4& v) const {
  glProgramUniform4fv(id(), location(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, const glm::mat4& v) const {
  glProgramUniformMatrix4fv(id(), location(n), 1, GL_FALSE, glm::value_ptr(v));
}

}  // namespace penumbra::gl
