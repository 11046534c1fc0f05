// Benchmark (not a test): per-stage times of techniques and of `raytrace` (same samples) on a
// scene, measured in one run on one machine, with the ratio of each technique's total to the
// reference's. Warm-up frames first, then the median and the spread (min..max) of each stage
// over the timed frames. Stages are timed with glFinish and a steady clock (GL timer queries
// are not meaningful on llvmpipe). Also prints each technique's statistics and render-target
// memory.
//
//   penumbra_bench [SCENE] [-W 512] [-H 512] [--samples 1,16,64] [--techniques hard-sv,dcs]
//                  [--frames 5] [--warmup 1] [--backend egl] [--json FILE]
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/files.h"
#include "core/log.h"
#include "gl/context.h"
#include "pipeline/renderer.h"
#include "scene/scene.h"
#include "bench_common.h"
#include "studies.h"

using namespace penumbra;

using bench::Spread;

namespace penumbra::bench {

int techniqueTimings(const TimingOptions& o, std::FILE* out) {
  setLogLevel("warn");
  const std::string &scenePath = o.scene, &jsonOut = o.json;
  const std::string pattern = toString(o.pattern), shading = toString(o.shading);
  const int width = o.width, height = o.height, frames = o.frames, warmup = o.warmup;
  const auto& sampleCounts = o.samples;
  const auto& techniques = o.techniques;
  try {
    Scene scene = loadScene(scenePath);
    auto ctx = gl::Context::create(o.backend);
    std::fprintf(out, "scene %s: %zu triangles, %dx%d, pattern %s, shading %s, renderer %s\n", scenePath.c_str(),
                 scene.triangleCount(), width, height, pattern.c_str(), shading.c_str(), ctx->renderer().c_str());
    nlohmann::json results;
    results["scene"] = scenePath;
    results["triangles"] = scene.triangleCount();
    results["renderer"] = ctx->renderer();
    results["width"] = width;
    results["height"] = height;
    results["pattern"] = pattern;
    results["shading"] = shading;
    for (int samples : sampleCounts) {
      RenderSettings s;
      s.width = width, s.height = height, s.sampling.count = samples;
      s.sampling.pattern = o.pattern;
      s.shading = o.shading;
      s.perSampleResults = false;  // no comparison here: time what a frame needs
      std::vector<TimedVariant> runs;
      for (const std::string& name : techniques) runs.push_back({name, name, {}, {}});
      runs.insert(runs.end(), o.variants.begin(), o.variants.end());
      runs.push_back({"raytrace", "raytrace", {}, {}});
      std::map<std::string, double> totals;
      for (const TimedVariant& run : runs) {
        const std::string& name = run.label;
        Renderer renderer(*ctx, scene, s);
        auto tech = makeTechnique(run.technique, TechniqueParams(run.params));
        bench::Timing timing = bench::timeFrames(renderer, *tech, frames, warmup);
        FrameResult last = timing.last;
        if (!run.profile.empty()) {  // the statistics of a profiled frame (not timed)
          std::vector<std::string> p = run.params;
          p.insert(p.end(), run.profile.begin(), run.profile.end());
          Renderer profiled(*ctx, scene, s);
          auto profiledTech = makeTechnique(run.technique, TechniqueParams(p));
          // A later frame, as the timed ones (dcs plans a light's later frames from its first).
          for (int i = 0; i < std::max(warmup, 1); ++i) profiled.render(*profiledTech);
          last.statistics = profiled.render(*profiledTech).statistics;
        }
        std::string key = name + "@" + std::to_string(samples);
        std::fprintf(out, "\n%s, %d sample(s) (%d frames after %d warm-up)%s\n  %-18s %10s %10s %10s\n", name.c_str(),
                     samples, frames, warmup, run.profile.empty() ? "" : ", statistics of a profiled frame", "stage",
                     "median ms", "min", "max");
        for (auto& [stage, sp] : timing.stages) {
          std::fprintf(out, "  %-18s %10.2f %10.2f %10.2f\n", stage.c_str(), sp.median, sp.min, sp.max);
          results[key]["stagesMs"][stage] = {{"median", sp.median}, {"min", sp.min}, {"max", sp.max}};
        }
        Spread sp = timing.total;
        std::fprintf(out, "  %-18s %10.2f %10.2f %10.2f\n", "total", sp.median, sp.min, sp.max);
        results[key]["totalMs"] = {{"median", sp.median}, {"min", sp.min}, {"max", sp.max}};
        results[key]["memoryBytes"] = last.memoryBytes;
        std::fprintf(out, "  render targets + buffers: %.1f MiB\n", double(last.memoryBytes) / (1024.0 * 1024.0));
        for (auto& [k, v] : last.statistics) {
          std::fprintf(out, "  %s = %g\n", k.c_str(), v);
          results[key]["statistics"][k] = v;
        }
        totals[name] = sp.median;
      }
      std::fprintf(out, "\n%d sample(s): total time relative to raytrace:", samples);
      for (auto& [name, t] : totals) {
        std::fprintf(out, "  %s %.2fx", name.c_str(), totals["raytrace"] / t);
        results["speedupOverRaytrace@" + std::to_string(samples)][name] = totals["raytrace"] / t;
      }
      std::fprintf(out, "  (> 1: faster than raytrace)\n");
    }
    if (!jsonOut.empty()) writeTextFile(jsonOut, results.dump(2) + "\n");
  } catch (const Error& e) {
    std::fprintf(stderr, "penumbra_bench: %s\n", e.what());
    return int(e.exitCode());
  }
  return 0;
}

}  // namespace penumbra::bench
