// Replays every seed of tests/fuzz/corpus/<format>/ and every input the fuzzers once broke the
// loader with (tests/fuzz/regressions/<format>/) through the same harness the fuzz targets use:
// each must load into a sane scene or be rejected with one penumbra::Error line naming the file
// (hard-cases.md, "Bad inputs: expected behaviour"). Built with every compiler, so the inputs
// stay checked without clang/libFuzzer; under tests/sanitize.sh they also run with ASan/UBSan.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/log.h"
#include "fuzz_harness.h"

namespace penumbra::fuzz {
namespace {

namespace fs = std::filesystem;

long peakResidentKiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

struct Counts {
  int loaded = 0, rejected = 0;
};

// Replays one folder (<root>/<format>/*) and returns the counts.
Counts replay(const std::string& root, const std::string& format) {
  Counts counts;
  const fs::path dir = fs::path(PENUMBRA_SOURCE_DIR) / "tests/fuzz" / root / format;
  if (!fs::is_directory(dir)) return counts;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const long peakBefore = peakResidentKiB();
    const auto start = std::chrono::steady_clock::now();
    const Verdict v = loadInput(format, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(v.problem, "") << file;
    // The fuzz rule, measured: the peak resident set may not grow by 1 GiB, nor a load take 10 s
    // on any input.
    EXPECT_LT(double(peakResidentKiB() - peakBefore) * 1024.0, double(kMaxInputBytes)) << file;
    EXPECT_LT(seconds, kMaxInputSeconds) << file;
    (v.loaded ? counts.loaded : counts.rejected)++;
  }
  std::printf("[          ] %s/%s: %d loaded, %d rejected\n", root.c_str(), format.c_str(), counts.loaded,
              counts.rejected);
  return counts;
}

class FuzzReplay : public ::testing::TestWithParam<std::string> {
 protected:
  static void SetUpTestSuite() { setLogLevel("off"); }
};

// The seed corpus holds valid and malformed files of every format: both outcomes must occur,
// so a loader that rejects everything (or accepts everything) fails here.
TEST_P(FuzzReplay, CorpusLoadsOrIsRejectedCleanly) {
  const Counts c = replay("corpus", GetParam());
  EXPECT_GT(c.loaded, 0) << "no seed of " << GetParam() << " loads";
  EXPECT_GT(c.rejected, 0) << "no malformed seed of " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Formats, FuzzReplay, ::testing::ValuesIn(formats()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// Every input a fuzzer once broke the loader with, kept after the fix (the reason is in
// tests/fuzz/regressions/README.md).
TEST(FuzzRegressions, LoadOrAreRejectedCleanly) {
  setLogLevel("off");
  int total = 0;
  for (const std::string& format : formats()) {
    const Counts c = replay("regressions", format);
    total += c.loaded + c.rejected;
  }
  EXPECT_GT(total, 0) << "tests/fuzz/regressions/ is empty";
}

}  // namespace
}  // namespace penumbra::fuzz
