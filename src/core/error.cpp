#include "core/error.h"

#include <cstdio>
#include <cstdlib>

namespace penumbra {

void checkFailed(const char* expr, const char* file, int line, const std::string& msg) {
  std::fprintf(stderr, "penumbra: internal check failed: %s (%s:%d) %s\n", expr, file, line,
               msg.c_str());
  std::abort();
}

}  // namespace penumbra
