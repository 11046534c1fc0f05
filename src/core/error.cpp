#include "core/error.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace penumbra {

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
  std::fprintf(stderr, "penumbra: internal check failed: %s (%s:%d) %s\n", expr, file, line,
               msg.c_str());
  std::abort();
}

}  // namespace penumbra
