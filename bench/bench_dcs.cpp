// Benchmark (not a test) of the DCS paper's studies, in one run on one machine: the covered-
// sample modes (exact / naive / lut) and N = 16 against 64 (DCS paper 8.2: DCS16 about 5x faster
// than DCS64, lut 25-33% faster than naive), the semi-opaque overhead (paper: < 4%), eq. 3
// against eq. 6 (paper: 8-12%), interleaving's cost, and the memory of every buffer at the
// paper's Table 1 configuration (1024 x 1024) next to its figures.
//
//   penumbra_bench_dcs [SCENE] [--semi SCENE] [-W 512] [-H 512] [--frames 5] [--warmup 1]
//                      [--backend egl] [--json FILE]
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "bench_common.h"
#include "studies.h"
#include "core/error.h"
#include "core/files.h"
#include "core/log.h"
#include "core/metrics.h"
#include "gl/context.h"
#include "pipeline/renderer.h"
#include "scene/scene.h"

using namespace penumbra;
using bench::frameStatistic;

namespace {

double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

}  // namespace

namespace penumbra::bench {

int dcsStudies(const DcsStudyOptions& o, std::FILE* out) {
  setLogLevel("warn");
  const std::string &scenePath = o.scene, &semiPath = o.semi, &jsonOut = o.json;
  const int width = o.width, height = o.height, frames = o.frames, warmup = o.warmup;
  try {
    auto ctx = gl::Context::create(o.backend);
    Scene scene = loadScene(scenePath);
    nlohmann::json results;
    results["renderer"] = ctx->renderer();
    results["scene"] = scenePath;
    results["width"] = width, results["height"] = height, results["frames"] = frames, results["warmup"] = warmup;
    std::fprintf(out, "DCS studies: %s (%zu triangles), %dx%d, median of %d frames after %d warm-up, renderer %s\n",
                 scenePath.c_str(), scene.triangleCount(), width, height, frames, warmup, ctx->renderer().c_str());
    auto settingsFor = [&](int n) {
      RenderSettings s;
      s.width = width, s.height = height, s.sampling.count = n;
      s.perSampleResults = false;
      return s;
    };
    auto run = [&](const Scene& sc, const RenderSettings& s, const std::string& technique) {
      Renderer r(*ctx, sc, s);
      auto t = makeTechnique(technique);
      return bench::timeFrames(r, *t, frames, warmup);
    };

    std::fprintf(out, "\n1. Covered-sample modes and sample counts (total ms, wedge stage ms)\n");
    std::fprintf(out, "  %-10s %12s %12s %12s %12s\n", "technique", "N=16 total", "wedges", "N=64 total", "wedges");
    std::map<std::string, std::map<int, double>> totals;
    for (const char* name : {"dcs", "dcs-naive", "dcs-lut"}) {
      std::fprintf(out, "  %-10s", name);
      for (int n : {16, 64}) {
        bench::Timing t = run(scene, settingsFor(n), name);
        totals[name][n] = t.total.median;
        std::fprintf(out, " %12.1f %12.1f", t.total.median, t.stage("dcs wedges"));
        results["modes"][name][std::to_string(n)] = {{"totalMs", t.total.median},
                                                     {"wedgesMs", t.stage("dcs wedges")},
                                                     {"minMs", t.total.min},
                                                     {"maxMs", t.total.max}};
      }
      std::fprintf(out, "\n");
    }
    for (int n : {16, 64})
      std::fprintf(out, "  N=%d: lut / naive time %.2f (paper: 0.67-0.75), lut / exact %.2f\n", n,
                   totals["dcs-lut"][n] / totals["dcs-naive"][n], totals["dcs-lut"][n] / totals["dcs"][n]);
    std::fprintf(out, "  exact: N=64 / N=16 time %.2f (paper: DCS16 about 5x faster than DCS64)\n",
                 totals["dcs"][64] / totals["dcs"][16]);

    std::fprintf(out, "\n2. Direct illumination: eq. 3 (modulate) against eq. 6 (per sample), dcs\n");
    for (int n : {16, 64}) {
      RenderSettings s3 = settingsFor(n), s6 = settingsFor(n);
      s6.shading = ShadingMode::PerSample;
      bench::Timing t3 = run(scene, s3, "dcs"), t6 = run(scene, s6, "dcs");
      double mean = 0;
      for (float v : t6.last.color.data) mean += v;
      mean /= double(t6.last.color.data.size());
      double diff = compareImages(t3.last.color, t6.last.color, {}, t6.last.gbuffer.valid).rmse / mean;
      std::fprintf(
          out,
          "  N=%-3d eq. 3 %8.1f ms (shading %5.1f)  eq. 6 %8.1f ms (shading %5.1f)  +%.1f%%  image RMSE %.3f x mean\n",
          n, t3.total.median, t3.stage("shading"), t6.total.median, t6.stage("shading"),
          100.0 * (t6.total.median / t3.total.median - 1.0), diff);
      results["shading"][std::to_string(n)] = {
          {"eq3Ms", t3.total.median}, {"eq6Ms", t6.total.median}, {"relativeImageRmse", diff}};
    }

    std::fprintf(out, "\n3. Interleaved sampling (4 x 4 sets) and its filter, dcs\n");
    for (int n : {16, 64}) {
      RenderSettings si = settingsFor(n);
      si.sampling.pattern = PixelPattern::Interleaved;
      bench::Timing tc = run(scene, settingsFor(n), "dcs"), ti = run(scene, si, "dcs");
      std::fprintf(out, "  N=%-3d correlated %8.1f ms  interleaved %8.1f ms (filter %.1f ms, %.1f%% of the frame)\n", n,
                   tc.total.median, ti.total.median, ti.stage("interleave filter"),
                   100.0 * ti.stage("interleave filter") / ti.total.median);
      results["interleaving"][std::to_string(n)] = {{"correlatedMs", tc.total.median},
                                                    {"interleavedMs", ti.total.median},
                                                    {"filterMs", ti.stage("interleave filter")}};
    }

    std::fprintf(out, "\n4. Semi-opaque occluders: %s against its opaque twin\n", semiPath.c_str());
    Scene semi = loadScene(semiPath), opaque = semi;
    for (auto& m : opaque.materials) m.opacity = 1.0f;
    for (int n : {16, 64}) {
      bench::Timing to = run(opaque, settingsFor(n), "dcs"), tp = run(semi, settingsFor(n), "dcs"),
                    ts = run(semi, settingsFor(n), "dcs-sum");
      std::fprintf(
          out,
          "  N=%-3d opaque %8.1f ms (base %g)  product %8.1f ms (base %g, %+.1f%%)  sum %8.1f ms (base %g, %+.1f%%)\n",
          n, to.total.median, frameStatistic(to.last, "counterBase"), tp.total.median,
          frameStatistic(tp.last, "counterBase"), 100.0 * (tp.total.median / to.total.median - 1.0), ts.total.median,
          frameStatistic(ts.last, "counterBase"), 100.0 * (ts.total.median / to.total.median - 1.0));
      results["semiOpaque"][std::to_string(n)] = {
          {"opaqueMs", to.total.median}, {"productMs", tp.total.median}, {"sumMs", ts.total.median}};
    }

    std::fprintf(out, "\n5. Memory at 1024 x 1024 (the paper's Table 1), dcs-lut with interleaving, one frame each\n");
    for (int n : {16, 64}) {
      RenderSettings s = settingsFor(n);
      s.width = s.height = 1024;
      s.sampling.pattern = PixelPattern::Interleaved;
      Renderer r(*ctx, scene, s);
      auto t = makeTechnique("dcs-lut");
      FrameResult f = r.render(*t);
      double px = 1024.0 * 1024.0, targets = frameStatistic(f, "targets");
      double sets = double(s.sampling.interleaveK * s.sampling.interleaveK);
      struct Row {
        const char* what;
        std::string ours;
        double oursMiB;
        const char* paper;
      };
      std::vector<Row> rows = {
          {"(a) silhouettes", "edges + incidences (static) + ids", -1.0, "5 MB TFB"},
          {"(b) sample positions", "vec4 x N x sets", mib(16.0 * n * sets), "128 B"},
          {"(c) edge LUT", "(512^2 + 6 x 64^2) RGBA32UI x sets", mib((512.0 * 512 + 6 * 64 * 64) * 16 * sets),
           "4.375 MB"},
          {"(d) per-light LUT", "vec4 luminance x N x sets", mib(16.0 * n * sets), "12 KB"},
          {"(e) colour", "RGBA32F", mib(16 * px), "8 MB (RGBA16F)"},
          {"(f) depth", "DEPTH32F", mib(4 * px), "3 MB (DEPTH24)"},
          {"(g) v-buffer", "RGBA32F", mib(16 * px), "3 MB (RGB8)"},
          {"(h) discontinuity", "none (G-buffer normals)", 0.0, "1 MB"},
          {"(i) temp filtered", "RGBA32F", mib(16 * px), "4 MB"},
          {"(j) deferred (G-buffer)", "position, normal RGBA32F; albedo RGBA16F", mib(40 * px), "12 MB (RGB32F)"},
          {"(k) DC-buffers", std::to_string(int(targets)) + " x RGBA32F", mib(16 * px * targets),
           n == 16 ? "16 MB (1 x RGBA32F)" : "32 MB (2 x RGBA32F)"},
          {"    D(c), checksum, bound", "R32F + RG32F + R32F", mib(16 * px), "(in the stencil)"}};
      std::fprintf(out, "  N=%d (counter base %g, %g targets): measured total %.1f MiB\n", n,
                   frameStatistic(f, "counterBase"), targets, mib(double(f.memoryBytes)));
      std::fprintf(out, "    %-26s %-44s %10s   %s\n", "buffer", "here", "MiB", "paper");
      for (auto& row : rows) {
        if (row.oursMiB < 0)
          std::fprintf(out, "    %-26s %-44s %10s   %s\n", row.what, row.ours.c_str(), "scene", row.paper);
        else
          std::fprintf(out, "    %-26s %-44s %10.3f   %s\n", row.what, row.ours.c_str(), row.oursMiB, row.paper);
        results["memory"][std::to_string(n)][row.what] = row.oursMiB;
      }
      results["memory"][std::to_string(n)]["measuredTotalMiB"] = mib(double(f.memoryBytes));
    }
    if (!jsonOut.empty()) writeTextFile(jsonOut, results.dump(2) + "\n");
  } catch (const Error& e) {
    std::fprintf(stderr, "penumbra_bench_dcs: %s\n", e.what());
    return int(e.exitCode());
  }
  return 0;
}

}  // namespace penumbra::bench
