// Benchmark (not a test): per-stage times of `hard-sv` and `raytrace` (same samples) on a scene,
// measured in one run on one machine. Warm-up frames first, then the median and the spread
// (min..max) of each stage over the timed frames. Stages are timed with glFinish and a steady
// clock (GL timer queries are not meaningful on llvmpipe).
//
//   penumbra_bench_hard_sv [SCENE] [-W 512] [-H 512] [--samples 1] [--frames 5] [--warmup 1]
//                          [--backend egl] [--json FILE]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/log.h"
#include "gl/context.h"
#include "pipeline/renderer.h"
#include "scene/scene.h"

using namespace penumbra;

namespace {

struct Spread {
  double median, min, max;
};

Spread spread(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  std::size_t n = v.size();
  double med = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {med, v.front(), v.back()};
}

}  // namespace

int main(int argc, char** argv) {
  setLogLevel("warn");
  CLI::App app{"per-stage timing of hard-sv and raytrace"};
  std::string scenePath = "scenes/engine.json", backend = "egl", jsonOut;
  int width = 512, height = 512, samples = 1, frames = 5, warmup = 1;
  app.add_option("scene", scenePath);
  app.add_option("-W", width);
  app.add_option("-H", height);
  app.add_option("--samples", samples);
  app.add_option("--frames", frames);
  app.add_option("--warmup", warmup);
  app.add_option("--backend", backend);
  app.add_option("--json", jsonOut);
  CLI11_PARSE(app, argc, argv);
  try {
    Scene scene = loadScene(scenePath);
    auto ctx = gl::Context::create(gl::parseBackend(backend));
    RenderSettings s;
    s.width = width, s.height = height, s.sampling.count = samples;
    std::printf("scene %s: %zu triangles, %dx%d, %d sample(s), renderer %s\n", scenePath.c_str(),
                scene.triangleCount(), width, height, samples, ctx->renderer().c_str());
    nlohmann::json out;
    out["scene"] = scenePath;
    out["triangles"] = scene.triangleCount();
    out["renderer"] = ctx->renderer();
    std::map<std::string, double> totals;
    for (const char* name : {"hard-sv", "raytrace"}) {
      Renderer renderer(*ctx, scene, s);
      auto tech = findTechnique(name).create();
      std::map<std::string, std::vector<double>> stages;
      std::vector<double> total;
      for (int f = 0; f < warmup + frames; ++f) {
        FrameResult r = renderer.render(*tech);
        if (f < warmup) continue;
        double t = 0;
        for (auto& st : r.timer.stages()) {
          if (st.stage == "prepare") continue;  // once per scene, reported by the warm-up
          stages[st.stage].push_back(st.ms);
          t += st.ms;
        }
        total.push_back(t);
      }
      std::printf("\n%s (%d frames after %d warm-up)\n  %-18s %10s %10s %10s\n", name, frames, warmup, "stage",
                  "median ms", "min", "max");
      for (auto& [stage, v] : stages) {
        Spread sp = spread(v);
        std::printf("  %-18s %10.2f %10.2f %10.2f\n", stage.c_str(), sp.median, sp.min, sp.max);
        out[name]["stagesMs"][stage] = {{"median", sp.median}, {"min", sp.min}, {"max", sp.max}};
      }
      Spread sp = spread(total);
      std::printf("  %-18s %10.2f %10.2f %10.2f\n", "total", sp.median, sp.min, sp.max);
      out[name]["totalMs"] = {{"median", sp.median}, {"min", sp.min}, {"max", sp.max}};
      totals[name] = sp.median;
    }
    std::printf("\nraytrace / hard-sv total time: %.2fx\n", totals["raytrace"] / totals["hard-sv"]);
    out["ratioRaytraceOverHardSv"] = totals["raytrace"] / totals["hard-sv"];
    if (!jsonOut.empty()) std::ofstream(jsonOut) << out.dump(2) << "\n";
  } catch (const Error& e) {
    std::fprintf(stderr, "penumbra_bench_hard_sv: %s\n", e.what());
    return int(e.exitCode());
  }
  return 0;
}
