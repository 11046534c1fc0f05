#include "gl/shader_source.h"

#include <algorithm>
#include <cctype>
#include <regex>
#include <sstream>

#include "gl/objects.h"

namespace penumbra::gl {
namespace {

// Lines of file k are numbered k * kFileLines + n: Mesa reports a #line's line numbers but not
// always its source-string number (an undeclared identifier in an included file came back as
// source 0), so the file travels in the line number and nameLogLocations decodes it.
constexpr int kFileLines = 100000;

std::string lineDirective(int file, int line) { return "#line " + std::to_string(file * kFileLines + line) + "\n"; }

// Appends `src` (file number `index`) to `out` with its #include lines resolved. A file is
// inlined once per stage, except headers (*.h, include-guarded): those are inlined wherever
// they are included, since a first inclusion may sit in an #ifdef branch the stage leaves out.
void resolveIncludes(const std::string& src, int index, std::vector<std::string>& files, std::string& out) {
  std::istringstream in(src);
  std::string line;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    auto pos = line.find("#include \"");
    if (pos != std::string::npos && line.find_first_not_of(" \t") == pos) {
      // By file name: a path (`#include "shading/shaders/shading.h"`, as C++ includes it through
      // its layer's include root) names the embedded file of its last component.
      std::string name = line.substr(pos + 10, line.find('"', pos + 10) - pos - 10);
      name = name.substr(name.rfind('/') + 1);
      auto seen = std::find(files.begin(), files.end(), name);
      const bool header = name.size() > 2 && name.compare(name.size() - 2, 2, ".h") == 0;
      if (seen == files.end() || header) {
        int included = int(seen - files.begin());
        if (seen == files.end()) {
          files.push_back(name);
          included = int(files.size()) - 1;
        }
        out += lineDirective(included, 1);
        resolveIncludes(shaderSource(name), included, files, out);
      }
      // The next line of this file.
      out += lineDirective(index, lineNo + 1);
      continue;
    }
    out += line + "\n";
  }
}

// Whether `name` occurs in `text` as a whole identifier.
bool mentions(const std::string& text, const std::string& name) {
  auto ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
    const std::size_t end = at + name.size();
    if ((at == 0 || !ident(text[at - 1])) && (end == text.size() || !ident(text[end]))) return true;
  }
  return false;
}

}  // namespace

ShaderText assembleShader(const std::string& file, const std::vector<std::string>& defines) {
  ShaderText s;
  s.files = {file, "shared.h"};
  std::string body = lineDirective(1, 1) + shaderSource("shared.h") + "\n" + lineDirective(0, 1);
  resolveIncludes(shaderSource(file), 0, s.files, body);
  // Only the defines this stage's text names: a stage that does not depend on a define keeps
  // the same text across a program's variants, so the driver's shader cache compiles it once
  // (dcs: the geometry shader of every counter layout).
  s.text = "#version 450 core\n";
  for (auto& d : defines) {
    const std::string name = d.substr(0, d.find_first_of(" ("));
    if (mentions(body, name)) s.text += "#define " + d + "\n";
  }
  s.text += body;
  return s;
}

std::string nameLogLocations(const std::string& log, const std::vector<std::string>& files) {
  // At the start of each line of the log, as both drivers write it: "S:L(C)" or "S(L)".
  static const std::regex location(R"((^|\n)(\d+)(?::(\d+)\((\d+)\)|\((\d+)\)))");
  std::string out;
  std::size_t last = 0;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), location); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    const bool mesa = m[3].matched;
    const long coded = std::stol(mesa ? m[3].str() : m[5].str());
    const std::size_t file = std::size_t(coded / kFileLines);
    out += log.substr(last, std::size_t(m.position(0)) - last) + m[1].str();
    if (file < files.size())
      out += files[file] + ":" + std::to_string(coded % kFileLines) + (mesa ? "(" + m[4].str() + ")" : "");
    else
      out += m[0].str().substr(m[1].length());
    last = std::size_t(m.position(0) + m.length(0));
  }
  out += log.substr(last);
  for (auto& c : out)
    if (c == '\n') c = ' ';
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace penumbra::gl
