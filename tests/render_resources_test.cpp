// Resource hygiene: repeated renders in one process leak no GL objects (the wrappers'
// live-object counts, gl::liveObjectCount) and no memory (the heap in use and VmRSS after
// warm-up grow less than their bounds), and give the same image every time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <malloc.h>
#include <numeric>
#include <string>
#include <vector>

#include "gl/objects.h"
#include "render_test_util.h"
#include "scene/scene.h"

namespace penumbra::test {
namespace {

long rssKiB() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

// Bytes the allocator has handed out and not had back, over every arena and mmap'd block
// (glibc's mallinfo2): a leak grows it, fragmentation and freed pages the allocator keeps do not.
long heapInUseKiB() {
  const struct mallinfo2 m = mallinfo2();
  return long((m.uordblks + m.hblkhd) / 1024);
}

std::vector<long> liveCounts() {
  std::vector<long> v;
  for (int k = 0; k < int(gl::Kind::Count); ++k) v.push_back(gl::liveObjectCount(gl::Kind(k)));
  return v;
}

std::string describe(const std::vector<long>& v) {
  std::string s;
  for (int k = 0; k < int(gl::Kind::Count); ++k)
    s += std::string(gl::toString(gl::Kind(k))) + " " + std::to_string(v[k]) + ", ";
  return s;
}

bool sameBits(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels &&
         std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

struct Case {
  const char* technique;
  std::vector<std::string> params;
};
const std::vector<Case> kCases = {{"hard-sv", {}},       {"dcs", {}},           {"mvr", {"map=128"}},
                                  {"vwss", {"map=128"}}, {"pcss", {"map=128"}}, {"vssm", {"map=128"}}};

// Two measures of memory growth over the measured renders, after three warm-up rounds that fill
// the driver's and the allocator's caches. The leak criterion is the heap in use (glibc's
// mallinfo2 over every arena: what was allocated and not freed; fragmentation and pages the
// allocator keeps do not count): a leak of one 128x128 RGBA32F target (256 KiB) per render would
// add 21 MiB over the 84 measured renders, against an 8 MiB bound. Twenty runs on llvmpipe
// (tests/spread.sh, 2026-12-07): heap -1.7 to +2.3 MiB (median 0.3); a reused renderer's 16
// frames -1.0 to +0.4 MiB; on zink a reused renderer's +2.3 to +3.75 MiB (two runs, the same to
// 10 KiB: lavapipe state per frame while penumbra's objects stay put). VmRSS, the backstop for
// memory outside malloc (llvmpipe's JIT code pages), is noisier: the same twenty runs -1.2 to
// +7.2 MiB (median 1.1), and a CI run of the whole suite +8.05 MiB (it failed the 8 MiB bound
// RSS had then), so its bound is 24 MiB: a per-render leak of JIT code or mapped memory the
// size of a target still crosses it.
constexpr long kHeapBoundKiB = 8 * 1024;
constexpr long kRssBoundKiB = 24 * 1024;
// zink over lavapipe (tests/zink.sh) keeps driver memory for every dcs program set a fresh
// renderer compiles and deletes: measured +3.6 MiB per dcs render, steady over 17 rounds, and
// +8.8 MiB with MESA_SHADER_CACHE_DISABLE=true (it scales with the shader compilation work),
// while every GL object penumbra made is deleted (the live counts below return to 0) and the
// same renders on llvmpipe grow by 8 KiB. The driver's own, not ours: on zink the dcs renders'
// growth is bounded per render (with a margin over what it measures), the other techniques'
// renders keep kRssBoundKiB together. Since shader headers were inlined wherever included
// (more text a program) it measures 4.5-5.1 MiB a render (4 runs, 2026-12-02), against the
// 5 MiB bound it had: 8 MiB then. Since the cut wedge solids (dcs_wedge.geom builds each
// wedge's polyhedron: a geometry shader that takes llvmpipe 4.6 s to compile where the old one
// took 1.35 s) it measures 24.8 MiB a render (2026-12-06): 32 MiB now. The way down is the
// polyhedra built by a compute pass, compiled once a process (an open item).
// On zink the test bounds the whole growth by one budget, kRssBoundKiB and this much per dcs
// render: charging the dcs renders what RSS grew across each of them and the rest the remainder
// left no margin (the driver frees some of a render's memory only later: over twenty runs the
// remainder spread from -21.7 to +8.1 MiB, 72 KiB under its 8 MiB bound at worst). Twenty runs on zink (2026-12-06):
// the dcs renders 24.9-27.5 MiB each, the whole growth at most 8.1 + 14 x 27.5 = 394 MiB against a budget of 8 + 14 x
// 32 = 456 MiB.
constexpr long kZinkDcsRenderBoundKiB = 32 * 1024;
constexpr int kSize = 128, kSamples = 8;
constexpr int kWarmupRounds = 3, kRounds = 14;  // 6 x 17 = 102 renders

// ASan's quarantine keeps freed memory mapped and its allocator is not glibc's: neither measure
// says anything there (LeakSanitizer checks leaks instead), so they are only checked in
// uninstrumented builds.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kCheckMemory = false;
#else
constexpr bool kCheckMemory = true;
#endif

// A fresh Renderer and technique per frame (what compare does per technique): every GL object
// is deleted again, so the live counts return to the baseline after each frame, and every frame
// is bit-identical to the first of its technique.
TEST(RenderResources, FreshRenderersLeakNothing) {
  context();
  Scene scene = loadScene(scenePath("scenes/hard/15-two-plates.json"));
  const std::vector<long> baseline = liveCounts();
  std::vector<FrameResult> first(kCases.size());
  long during = 0;
  auto renderOnce = [&](std::size_t i) {
    Renderer renderer(context(), scene, settings(kSize, kSamples));
    auto tech = makeTechnique(kCases[i].technique, params(kCases[i].params));
    FrameResult f = renderer.render(*tech);
    during = std::max(during, gl::liveObjectCount());
    return f;
  };
  const bool zink = context().renderer().find("zink") != std::string::npos;
  long rss0 = 0, heap0 = 0, zinkDcsGrowth = 0;
  int renders = 0, zinkDcsRenders = 0;
  for (int r = 0; r < kWarmupRounds + kRounds; ++r) {
    if (r == kWarmupRounds) rss0 = rssKiB(), heap0 = heapInUseKiB();
    for (std::size_t i = 0; i < kCases.size(); ++i) {
      const long before = rssKiB();
      FrameResult f = renderOnce(i);
      if (zink && r >= kWarmupRounds && std::strcmp(kCases[i].technique, "dcs") == 0)
        zinkDcsGrowth += rssKiB() - before, ++zinkDcsRenders;
      ++renders;
      if (r == 0) {
        first[i] = std::move(f);
        continue;
      }
      EXPECT_TRUE(sameBits(f.color, first[i].color)) << kCases[i].technique << " round " << r << ": colour differs";
      ASSERT_EQ(f.lights.size(), first[i].lights.size());
      for (std::size_t l = 0; l < f.lights.size(); ++l)
        EXPECT_TRUE(sameBits(f.lights[l].visibility, first[i].lights[l].visibility))
            << kCases[i].technique << " round " << r << ": visibility differs";
    }
    EXPECT_EQ(liveCounts(), baseline) << "after round " << r << ": " << describe(liveCounts())
                                      << "baseline: " << describe(baseline);
  }
  const long rss1 = rssKiB(), heap1 = heapInUseKiB();
  // zink: the driver's memory per compiled dcs program set joins both budgets (see above).
  const long zinkAllowance = long(zinkDcsRenders) * kZinkDcsRenderBoundKiB;
  std::printf(
      "[ resources ] %d renders of %d px: live GL objects %ld before, up to %ld during a render, %ld after; "
      "over the last %d: heap in use %+ld KiB (bound %ld), VmRSS %ld KiB -> %ld KiB (%+ld KiB, bound %ld)%s\n",
      renders, kSize, std::accumulate(baseline.begin(), baseline.end(), 0L), during, gl::liveObjectCount(),
      kRounds * int(kCases.size()), heap1 - heap0, kHeapBoundKiB + zinkAllowance, rss0, rss1, rss1 - rss0,
      kRssBoundKiB + zinkAllowance, kCheckMemory ? "" : ", not checked under ASan");
  RecordProperty("heap_growth_kib", std::to_string(heap1 - heap0));
  RecordProperty("rss_growth_kib", std::to_string(rss1 - rss0));
  if (zink) {
    std::printf("[ resources ] zink: %d measured dcs renders, VmRSS grew by %ld KiB across them (%ld a render)\n",
                zinkDcsRenders, zinkDcsGrowth, zinkDcsGrowth / std::max(zinkDcsRenders, 1));
    RecordProperty("zink_dcs_rss_growth_kib_per_render", std::to_string(zinkDcsGrowth / std::max(zinkDcsRenders, 1)));
  }
  if (kCheckMemory) {
    EXPECT_LT(heap1 - heap0, kHeapBoundKiB + zinkAllowance)
        << "heap in use grew from " << heap0 << " to " << heap1 << " KiB";
    EXPECT_LT(rss1 - rss0, kRssBoundKiB + zinkAllowance) << "VmRSS grew from " << rss0 << " to " << rss1 << " KiB";
  }
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// One Renderer and technique rendering frame after frame (benchmarks, animation): the live
// counts stay where the first frame left them, the memory stays put, the image is identical.
// The bound holds on zink too: there dcs grew by 1.2 MiB a frame (19.9 MiB over the 16, CI
// 2026-12-03) while its GL objects stayed put, because Mesa 22.3's lavapipe compiled a new
// shader, never freed, at each draw of a program whose loops are bounded by uniforms. Those
// bounds are read from buffers now (src/techniques/dcs/shaders/common_dcs_pass.glsl, common_light.glsl): measured
// on zink over 16 frames with a warm shader cache, dcs +2.0-2.9 MiB (was +19.9 MiB); hard-sv
// +1.8-2.1 MiB, as before (a smaller growth, source not found); llvmpipe 0-64 KiB.
TEST(RenderResources, ReusedRendererIsStable) {
  context();
  Scene scene = loadScene(scenePath("scenes/hard/15-two-plates.json"));
  const std::vector<long> baseline = liveCounts();
  for (auto& c : kCases) {
    {
      Renderer renderer(context(), scene, settings(kSize, kSamples));
      auto tech = makeTechnique(c.technique, params(c.params));
      FrameResult first = renderer.render(*tech);
      // Warm-up: a second frame may keep what the first made. dcs's first frame of a light plans
      // its counters wide and its second from the measured bound (another program set), which
      // zink then builds once more on its next use (lavapipe's pipelines for the program set;
      // with one warm-up frame the first measured frame grew by 16-50 MiB, the 15 after it by
      // ~0.1 MiB each, 2026-12-05): the measured frames start after the second use.
      renderer.render(*tech);
      renderer.render(*tech);
      const std::vector<long> after = liveCounts();
      const long rss0 = rssKiB(), heap0 = heapInUseKiB();
      for (int i = 0; i < 16; ++i) {
        FrameResult f = renderer.render(*tech);
        EXPECT_TRUE(sameBits(f.color, first.color)) << c.technique << " frame " << i + 2;
        EXPECT_EQ(liveCounts(), after) << c.technique << " frame " << i + 2 << ": " << describe(liveCounts());
      }
      const long rssGrowth = rssKiB() - rss0, heapGrowth = heapInUseKiB() - heap0;
      std::printf(
          "[ resources ] reused renderer, %s: over 16 frames heap in use %+ld KiB (bound %ld), VmRSS %+ld KiB "
          "(bound %ld)%s\n",
          c.technique, heapGrowth, kHeapBoundKiB, rssGrowth, kRssBoundKiB,
          kCheckMemory ? "" : ", not checked under ASan");
      RecordProperty(std::string("heap_growth_kib_") + c.technique, std::to_string(heapGrowth));
      RecordProperty(std::string("rss_growth_kib_") + c.technique, std::to_string(rssGrowth));
      if (kCheckMemory) {
        EXPECT_LT(heapGrowth, kHeapBoundKiB) << c.technique;
        EXPECT_LT(rssGrowth, kRssBoundKiB) << c.technique;
      }
    }
    EXPECT_EQ(liveCounts(), baseline) << c.technique << " destroyed: " << describe(liveCounts());
  }
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// The limits checks in gl/objects.cpp: a texture or target beyond the GL's limits, or an
// allocation the GL cannot make, is a one-line penumbra::Error, not a GL error or a crash.
TEST(RenderResources, LimitsAreErrorsNotGlErrors) {
  context();
  const gl::Limits& l = gl::limits();
  EXPECT_GE(l.maxTextureSize, 1024);
  EXPECT_GE(l.maxArrayLayers, 256);
  EXPECT_GT(l.maxStorageBlockSize, 0);
  const long live = gl::liveObjectCount();
  auto expectError = [&](const char* what, auto&& f) {
    try {
      f();
      ADD_FAILURE() << what << ": no error";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      std::printf("[ limits ] %s: %s\n", what, e.what());
    }
    EXPECT_EQ(gl::liveObjectCount(), live) << what << ": an object leaked";
    EXPECT_EQ(gl::Context::takeErrorCount(), 0) << what << ": raised a GL error";
  };
  expectError("2D texture too wide", [&] { gl::Texture::make2D(GL_R32F, l.maxTextureSize + 1, 4); });
  expectError("array too deep", [&] { gl::Texture::make2DArray(GL_R32F, 4, 4, l.maxArrayLayers + 1); });
  expectError("empty framebuffer too large", [&] { gl::Framebuffer::empty(l.maxFramebufferWidth + 1, 4); });
  // Within the limits, but llvmpipe cannot allocate 4 GiB: GL_OUT_OF_MEMORY, reported as an Error.
  expectError("GL out of memory", [&] { gl::Texture::make2D(GL_RGBA32F, l.maxTextureSize, l.maxTextureSize); });
  // Beyond memory: 16 layers of 16384^2 RGBA32F = 64 GiB (refused before asking the GL).
  expectError("out of memory", [&] { gl::Texture::make2DArray(GL_RGBA32F, l.maxTextureSize, l.maxTextureSize, 16); });
  expectError("storage block too large", [&] {
    gl::Buffer b(std::size_t(l.maxStorageBlockSize) + 16, nullptr);
    b.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  });
}

}  // namespace
}  // namespace penumbra::test
