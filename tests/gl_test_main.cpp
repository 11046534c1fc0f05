// main() for tests that need a GL context: without one (no EGL display, no OSMesa) every test
// of the executable exits 77, which CTest reports as skipped (SKIP_RETURN_CODE), never as passed.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "core/log.h"
#include "gl/context.h"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  bool listing = false;
  for (int i = 1; i < argc; ++i) listing |= std::strncmp(argv[i], "--gtest_list_tests", 18) == 0;
  if (!listing) {
    penumbra::setLogLevel("warn");
    try {
      penumbra::gl::Context::create(penumbra::gl::Backend::Egl);
    } catch (const penumbra::Error& e) {
      std::fprintf(stderr, "no GL context: %s\n", e.what());
      return 77;
    }
  }
  return RUN_ALL_TESTS();
}
