// One input through the scene loader, shared by the libFuzzer targets (fuzz_main.cpp, clang
// only) and the always-built corpus replay test (replay_test.cpp), so both judge an input the
// same way. The contract is hard-cases.md "Bad inputs: expected behaviour": any input either
// loads into a sane scene or throws penumbra::Error with one line naming the file and the
// problem; never a crash, UB, another exception type, unbounded allocation or a hang (the last
// three are enforced by libFuzzer's -rss_limit_mb / -timeout and the sanitizers).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra::fuzz {

// The rule of a fuzz case (hard-cases.md, hostile inputs): no input may make the loader allocate
// more than 1 GiB or run longer than 10 s. The harness runs the loader under a memory budget of
// kMaxInputBytes (core/memory.h), so that what would need more is refused before it allocates;
// libFuzzer enforces both bounds (tests/fuzz/run.sh: -malloc_limit_mb, -timeout) and the replay
// test measures them (replay_test.cpp).
constexpr std::size_t kMaxInputBytes = std::size_t(1) << 30;
constexpr double kMaxInputSeconds = 10.0;

// The formats with a fuzz target: the input's bytes become a file of that extension. "exr" and
// "png" are texture files, loaded as the emission texture of a fixed scene.
const std::vector<std::string>& formats();

// A private folder holding the files a fuzzed scene JSON can refer to (cube.gltf, cube.bin,
// mesh.obj, tex.png, tex.exr). Created once per process, removed at exit.
const std::string& workspace();

struct Verdict {
  bool loaded = false;  // loadScene returned
  std::string message;  // the penumbra::Error text when rejected
  std::string problem;  // non-empty: the contract is broken (the fuzzer aborts on it)
};

// Writes `data` as <workspace>/input.<format> and loads it with penumbra::loadScene.
Verdict loadInput(const std::string& format, const std::uint8_t* data, std::size_t size);

}  // namespace penumbra::fuzz
