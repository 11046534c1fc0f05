#include "gl/shader_source.h"

#include <algorithm>
#include <regex>
#include <sstream>

#include "gl/objects.h"

namespace penumbra::gl {
namespace {

// Appends `src` (source string `index`) to `out` with its #include lines resolved.
void resolveIncludes(const std::string& src, int index, std::vector<std::string>& files, std::string& out) {
  std::istringstream in(src);
  std::string line;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    auto pos = line.find("#include \"");
    if (pos != std::string::npos && line.find_first_not_of(" \t") == pos) {
      std::string name = line.substr(pos + 10, line.find('"', pos + 10) - pos - 10);
      if (std::find(files.begin(), files.end(), name) == files.end()) {
        files.push_back(name);
        const int included = int(files.size()) - 1;
        out += "#line 1 " + std::to_string(included) + "\n";
        resolveIncludes(shaderSource(name), included, files, out);
      }
      // The next line of this file, under its own number.
      out += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(index) + "\n";
      continue;
    }
    out += line + "\n";
  }
}

}  // namespace

ShaderText assembleShader(const std::string& file, const std::vector<std::string>& defines) {
  ShaderText s;
  s.files = {file, "shared.h"};
  s.text = "#version 450 core\n";
  for (auto& d : defines) s.text += "#define " + d + "\n";
  s.text += "#line 1 1\n" + shaderSource("shared.h") + "\n#line 1 0\n";
  resolveIncludes(shaderSource(file), 0, s.files, s.text);
  return s;
}

std::string nameLogLocations(const std::string& log, const std::vector<std::string>& files) {
  // At the start of each line of the log, as both drivers write it.
  static const std::regex location(R"((^|\n)(\d+)(:\d+\(\d+\)|\(\d+\)))");
  std::string out;
  auto begin = std::sregex_iterator(log.begin(), log.end(), location);
  std::size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    const std::size_t index = std::size_t(std::stoul(m[2].str()));
    out += log.substr(last, std::size_t(m.position(0)) - last) + m[1].str();
    out += (index < files.size() ? files[index] : m[2].str()) + (m[3].str()[0] == ':' ? m[3].str() : ":" + m[3].str().substr(1, m[3].length() - 2));
    last = std::size_t(m.position(0) + m.length(0));
  }
  out += log.substr(last);
  for (auto& c : out)
    if (c == '\n') c = ' ';
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace penumbra::gl
