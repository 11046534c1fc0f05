// Benchmark (not a test): error against light size, the question engine developers ask (which
// approximation breaks first as the light grows). Each scene's lights are scaled from near a
// point to larger than its occluders; at each size, `compare` against the same-sample reference
// (every technique's visibility RMSE; the report, its Pareto plot among them, in
// DIR/<scene>/size-<scale>/). Per scene a line chart of error against the light's width
// (DIR/<scene>.svg) and a table (DIR/light-size.md, and on `out`).
//
//   penumbra_bench_light_size -o DIR [--scenes ...] [--scales 0.05,0.1,...] [--techniques ...]
//       [--samples 16] [-W 128] [--frames 1] [--warmup 1] [--backend egl]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"
#include "core/files.h"
#include "core/log.h"
#include "compare/compare.h"
#include "compare/plot.h"
#include "compare/report.h"
#include "gl/context.h"
#include "scene/scene.h"
#include "studies.h"
#include "techniques/registry.h"

namespace fs = std::filesystem;

namespace penumbra::bench {

namespace {

// The scene with every light's extent (a rect's sides, a disk's or a sphere's radius) times `scale`.
Scene withLightsScaled(Scene scene, double scale) {
  for (Light& l : scene.lights) l.size *= float(scale);
  return scene;
}

}  // namespace

int lightSizeStudy(const LightSizeOptions& o, std::FILE* out) {
  try {
    auto ctx = gl::Context::create(o.backend);
    fs::create_directories(o.outDir);
    std::fprintf(out,
                 "Error against light size: %zu scenes, lights scaled by %s, %d px wide, %d samples, visibility RMSE "
                 "against the same-sample reference; median of %d frames after %d warm-up; renderer %s\n\n",
                 o.scenes.size(), fmt::format("{}", fmt::join(o.scales, ", ")).c_str(), o.width, o.samples, o.frames,
                 o.warmup, ctx->renderer().c_str());
    std::string md;
    int failures = 0;
    for (const std::string& path : o.scenes) {
      const Scene base = loadScene(path);
      if (base.lights.empty()) throw Error(path, "the light-size study needs a light");
      const std::string name = fileNameComponent(base.name, "scene");
      // technique -> (light width, RMSE) per size
      std::map<std::string, std::vector<std::pair<double, double>>> rmse;
      std::map<std::string, std::vector<std::string>> failed;
      for (double scale : o.scales) {
        const Scene scene = withLightsScaled(base, scale);
        RenderSettings s;
        s.width = o.width;
        s.height = std::max(1, int(std::lround(double(o.width) * scene.height / scene.width)));
        s.sampling.count = o.samples;
        CompareOptions c;
        c.techniques = findTechniques(o.techniques);
        c.reference = findTechnique("raytrace");
        c.timingFrames = o.frames, c.warmup = o.warmup;
        c.outDir = (fs::path(o.outDir) / name / fmt::format("size-{}", scale)).string();
        c.writeImages = o.images, c.writeExr = false;
        c.progress = 0;
        fs::create_directories(c.outDir);
        PLOG_WARN("light-size: {} x{}", scene.name, scale);
        CompareResult r = compareTechniques(*ctx, scene, s, c);
        r.info["backend"] = gl::toString(o.backend);
        r.info["lightScale"] = scale;
        writeReport(r, c.outDir);
        const double width = double(scene.lights[0].size.x);
        for (const CompareRun& run : r.runs) {
          if (run.reference) continue;
          if (run.failed) {
            failed[run.technique].push_back(fmt::format("x{}: {}", scale, run.failure));
            ++failures;
            continue;
          }
          rmse[run.technique].emplace_back(width, run.errors.visibility.rmse);
        }
      }
      // The table: a row per technique, a column per size.
      std::string header = "| technique |", rule = "|---|";
      for (double scale : o.scales) {
        header += fmt::format(" {:.3g} |", double(base.lights[0].size.x) * scale);
        rule += "---|";
      }
      std::string section = fmt::format(
          "## {} ({})\n\nVisibility RMSE against the same-sample reference by light width (world units; "
          "the scene's own: {:.3g}). Chart: [{}.svg]({}.svg); each size's report, its speed-error plot "
          "among them: `{}/size-<scale>/`.\n\n{}\n{}\n",
          base.name, path, double(base.lights[0].size.x), name, name, name, header, rule);
      std::vector<ChartSeries> series;
      for (const std::string& t : o.techniques) {
        std::string row = "| " + t + " |";
        const auto& points = rmse[t];
        for (double scale : o.scales) {
          const double w = double(base.lights[0].size.x) * scale;
          const auto it = std::find_if(points.begin(), points.end(),
                                       [&](const auto& p) { return std::abs(p.first - w) <= 1e-6 * w; });
          row += it == points.end() ? " failed |" : fmt::format(" {:.4f} |", it->second);
        }
        section += row + "\n";
        series.push_back({t, findTechnique(t).family, points});
      }
      for (auto& [t, why] : failed) section += fmt::format("\n{} failed: {}\n", t, fmt::join(why, "; "));
      section += "\n";
      writeTextFile((fs::path(o.outDir) / (name + ".svg")).string(),
                    lineChartSvg("Error against light size: " + base.name, "light width (world units)",
                                 "visibility RMSE vs same-sample reference", series));
      std::fprintf(out, "%s", section.c_str());
      md += section;
      std::fflush(out);
    }
    writeTextFile((fs::path(o.outDir) / "light-size.md").string(), md);
    if (failures > 0) std::fprintf(out, "\n%d technique runs failed (named above)\n", failures);
    return failures > 0 ? 1 : 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "penumbra_bench_light_size: %s\n", e.what());
    return 1;
  }
}

}  // namespace penumbra::bench
