#include "core/error.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace penumbra {

std::string escapeControls(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f) {
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[u >> 4];
      out += hex[u & 15];
    }
  }
  return out;
}

std::string abbreviate(const std::string& value, std::size_t limit) {
  if (value.size() <= limit) return value;
  std::size_t cut = limit;
  // Not inside a UTF-8 sequence: back up over continuation bytes (10xxxxxx) to a lead byte.
  while (cut > 0 && (static_cast<unsigned char>(value[cut]) & 0xc0) == 0x80) --cut;
  return value.substr(0, cut) + "... (" + std::to_string(value.size()) + " characters)";
}

std::string fileProblem(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::not_found) return "no such file";
  if (ec) return ec.message();
  if (st.type() == fs::file_type::directory) return "is a folder, not a file";
  if (st.type() != fs::file_type::regular) return "is not a regular file (a device, socket or pipe)";
  return {};
}

void checkFailed(const char* expr, const char* file, int line, const std::string& msg) {
  std::fprintf(stderr, "penumbra: internal check failed: %s (%s:%d) %s\n", expr, file, line, msg.c_str());
  std::abort();
}

}  // namespace penumbra
