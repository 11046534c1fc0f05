// libFuzzer entry point: one binary per format (PENUMBRA_FUZZ_FORMAT, set by
// tests/fuzz/CMakeLists.txt). A broken contract (see fuzz_harness.h) aborts, so libFuzzer keeps
// the input as a crash artifact; crashes, UB, leaks, -rss_limit_mb and -timeout are caught by
// the sanitizers and libFuzzer themselves.
#include <cstdio>
#include <cstdlib>

#include "core/log.h"
#include "fuzz_harness.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  penumbra::setLogLevel("off");  // warnings of rejected inputs would flood the output
  penumbra::fuzz::workspace();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  const penumbra::fuzz::Verdict v = penumbra::fuzz::loadInput(PENUMBRA_FUZZ_FORMAT, data, size);
  if (!v.problem.empty()) {
    std::fprintf(stderr, "penumbra fuzz (%s): %s\n", PENUMBRA_FUZZ_FORMAT, v.problem.c_str());
    std::abort();
  }
  return 0;
}
