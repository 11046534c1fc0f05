// Benchmark (not a test): speed against error on every shipped scene (but the bunny crowd, issue
// 19's dcs scale case) and the built-in one, in one run on one
// machine. For each scene, `compare` with a samples sweep (the presets of every technique's
// curve) against the converged reference (raytrace-converged, 1024 stratified samples per
// pixel); each scene's report (index.html, report.json/.csv, plot.svg, PNG images) goes to
// DIR/<scene>/. Then the headline: per technique and sample count, the geometric mean over
// the scenes of the median frame time and of the visibility RMSE against the converged
// reference, how often the technique is on a scene's Pareto front, and the plot of those means
// (DIR/headline.svg, DIR/headline.md).
//
//   penumbra_bench_speed_error -o DIR [--scenes default,scenes/engine.json,...] [-W 128]
//       [--samples 8,16,32,64] [--techniques hard-sv,dcs,...] [--frames 3] [--warmup 1] [--backend egl]
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include <fmt/format.h>

#include "bench_common.h"
#include "core/error.h"
#include "core/files.h"
#include "core/log.h"
#include "gl/context.h"
#include "compare/compare.h"
#include "compare/report.h"
#include "scene/scene.h"
#include "studies.h"
#include "techniques/registry.h"

namespace fs = std::filesystem;

namespace penumbra::bench {

int speedErrorStudy(const SpeedErrorOptions& o, std::FILE* out) {
  const auto& scenes = o.scenes;
  const auto& techniques = o.techniques;
  const std::string& outDir = o.outDir;
  const int width = o.width, frames = o.frames, warmup = o.warmup;
  const bool images = o.images;
  std::string samples;
  for (int n : o.samples) samples += (samples.empty() ? "" : ",") + std::to_string(n);
  try {
    auto ctx = gl::Context::create(o.backend);
    fs::create_directories(outDir);
    std::fprintf(out,
                 "Speed against error: %zu scenes, %d px wide, samples %s, median of %d frames after %d warm-up "
                 "(glFinish + steady clock), visibility RMSE against raytrace-converged (1024 spp); renderer %s\n\n",
                 scenes.size(), width, samples.c_str(), frames, warmup, ctx->renderer().c_str());

    // Per (technique, samples): sums of logs over the scenes it ran on, and the scenes where it
    // failed (its row in that scene's report says why). The ratio to raytrace is taken per scene,
    // so a technique that failed somewhere is compared with raytrace on the same scenes.
    struct Acc {
      double logMs = 0, logErr = 0, logRatio = 0;
      int n = 0, front = 0;
      std::vector<std::string> failedOn;
    };
    std::map<std::pair<std::string, int>, Acc> acc;  // (technique, samples)
    std::vector<std::string> order;
    std::vector<int> sampleCounts;
    int failures = 0;
    for (const std::string& path : scenes) {
      Scene scene = path == "default" ? defaultScene() : loadScene(path);
      RenderSettings s;
      s.width = width;
      s.height = std::max(1, int(std::lround(double(width) * scene.height / scene.width)));
      CompareOptions c;
      c.techniques = findTechniques(techniques);
      c.reference = findTechnique("raytrace");
      c.convergedReference = findTechnique("raytrace-converged");
      c.sweeps = {SweepAxis::of("samples", o.samples)};
      c.converged = true;
      // The study's error is the visibility's: 1024 samples a pixel (the reference's own noise is
      // in each report), not the shaded image's 1e-3 target (up to 65536, hours over ten scenes).
      c.params = {"reference-samples=1024", "reference-max-samples=1024"};
      c.timingFrames = frames, c.warmup = warmup;
      c.outDir = (fs::path(outDir) / fileNameComponent(scene.name, "scene")).string();
      c.writeImages = images, c.writeExr = false;
      c.progress = 0;
      fs::create_directories(c.outDir);
      PLOG_WARN("speed-error: {} ({} triangles)", scene.name, scene.triangleCount());
      CompareResult r = compareTechniques(*ctx, scene, s, c);
      r.info["backend"] = gl::toString(o.backend);
      writeReport(r, c.outDir);
      std::fprintf(out, "== %s (%s, %zu triangles, %dx%d)\n%s", scene.name.c_str(), path.c_str(), scene.triangleCount(),
                   s.width, s.height, reportTable(r).c_str());
      // A failed run is its row's error in the scene's report; the headline names the scene
      // beside the technique's means (never a mean silently over fewer scenes), and the study
      // exits 1.
      for (auto& run : r.runs)
        if (run.failed) {
          PLOG_ERROR("speed-error: {}: {} @ {} failed: {}", scene.name, run.technique, r.presets[run.preset].label,
                     run.failure);
          acc[{run.technique, r.presets[run.preset].samples}].failedOn.push_back(scene.name);
          if (std::find(order.begin(), order.end(), run.technique) == order.end()) order.push_back(run.technique);
          ++failures;
        }

      const auto plotted = plottedRuns(r);
      const std::vector<std::size_t> front = paretoRuns(r);
      std::string frontText;
      for (auto i : front)
        frontText += fmt::format("{}{} @ {} ({:.1f} ms, {:.4f})", frontText.empty() ? "" : ", ", r.runs[i].technique,
                                 r.presets[r.runs[i].preset].label, r.runs[i].total.median, r.runs[i].plotError());
      std::fprintf(out, "Pareto front: %s\n\n", frontText.c_str());
      std::fflush(out);
      for (auto i : plotted) {
        const CompareRun& run = r.runs[i];
        int n = r.presets[run.preset].samples;
        if (std::find(sampleCounts.begin(), sampleCounts.end(), n) == sampleCounts.end()) sampleCounts.push_back(n);
        if (std::find(order.begin(), order.end(), run.technique) == order.end()) order.push_back(run.technique);
        Acc& a = acc[{run.technique, n}];
        const auto raytrace = std::find_if(r.runs.begin(), r.runs.end(), [&](const CompareRun& x) {
          return x.technique == "raytrace" && x.preset == run.preset && !x.failed;
        });
        if (raytrace == r.runs.end()) throw Error(scene.name, "no raytrace run at " + r.presets[run.preset].label);
        a.logRatio += std::log(run.total.median / raytrace->total.median);
        a.logMs += std::log(run.total.median);
        a.logErr += std::log(std::max(run.plotError(), 1e-6));
        a.n += 1;
        a.front += std::find(front.begin(), front.end(), i) != front.end();
      }
    }

    // The headline: geometric means over the scenes, as a table and as a CompareResult for
    // the same plot as each scene's.
    CompareResult headline;
    headline.info = {{"sceneName", fmt::format("geometric mean over {} scenes", scenes.size())}};
    std::sort(sampleCounts.begin(), sampleCounts.end());
    for (int n : sampleCounts) {
      ComparePreset p;
      p.samples = n, p.label = fmt::format("samples={}", n), p.values = {{"samples", std::to_string(n)}};
      headline.presets.push_back(p);
    }
    std::string md = fmt::format(
        "| technique | samples | ms (geo. mean) | x raytrace time | visibility RMSE vs converged (geo. mean) | on the "
        "Pareto front | scenes |\n|---|---|---|---|---|---|---|\n");
    std::fprintf(out, "Headline: geometric mean over %zu scenes (or those named)\n%-14s %7s %12s %12s %14s %8s  %s\n",
                 scenes.size(), "technique", "samples", "ms", "x raytrace", "RMSE vs conv", "front", "scenes");
    for (auto& t : order)
      for (std::size_t pi = 0; pi < headline.presets.size(); ++pi) {
        int n = headline.presets[pi].samples;
        auto it = acc.find({t, n});
        if (it == acc.end()) continue;
        const Acc& a = it->second;
        std::string ran = fmt::format("{} of {}", a.n, scenes.size());
        if (!a.failedOn.empty()) ran += fmt::format(" (failed on {})", fmt::join(a.failedOn, ", "));
        if (a.n == 0) {
          std::fprintf(out, "%-14s %7d %12s %12s %14s %8s  %s\n", t.c_str(), n, "-", "-", "-", "-", ran.c_str());
          md += fmt::format("| {} | {} | - | - | - | - | {} |\n", t, n, ran);
          continue;
        }
        double ms = std::exp(a.logMs / a.n), err = std::exp(a.logErr / a.n), ratio = std::exp(a.logRatio / a.n);
        std::fprintf(out, "%-14s %7d %12.1f %12.2f %14.4f %5d/%d  %s\n", t.c_str(), n, ms, ratio, err, a.front, a.n,
                     ran.c_str());
        md += fmt::format("| {} | {} | {:.1f} | {:.2f} | {:.4f} | {}/{} | {} |\n", t, n, ms, ratio, err, a.front, a.n,
                          ran);
        CompareRun run;
        run.technique = t, run.preset = pi, run.reference = t == "raytrace";
        run.family = findTechnique(t).family;
        run.total = {ms, ms, ms};
        TechniqueErrors e;
        e.visibility.rmse = err;
        run.converged = e;
        headline.runs.push_back(run);
      }
    // Which technique when, across the scenes (the same summary as each scene's report): the
    // headline's front and families' best, and the techniques that failed somewhere.
    for (auto& [key, a] : acc)
      if (!a.failedOn.empty()) {
        CompareRun failed;
        failed.technique = key.first, failed.family = findTechnique(key.first).family, failed.failed = true;
        failed.preset = std::size_t(std::find_if(headline.presets.begin(), headline.presets.end(),
                                                 [&](auto& p) { return p.samples == key.second; }) -
                                    headline.presets.begin());
        failed.failure = fmt::format("on {} (that scene's report says why)", fmt::join(a.failedOn, ", "));
        if (failed.preset < headline.presets.size()) headline.runs.push_back(failed);
      }
    std::string summary;
    for (const std::string& line : whichTechniqueWhen(headline)) summary += "- " + line + "\n";
    std::fprintf(out, "\nWhich technique when (geometric means over the scenes):\n%s", summary.c_str());
    writeTextFile((fs::path(outDir) / "summary.md").string(), summary);
    writeTextFile((fs::path(outDir) / "headline.md").string(), md);
    writeTextFile((fs::path(outDir) / "headline.svg").string(), speedErrorSvg(headline));
    if (failures > 0)
      std::fprintf(out, "\n%d technique runs failed (named above and in their scenes' reports)\n", failures);
    return failures > 0 ? 1 : 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "penumbra_bench_speed_error: %s\n", e.what());
    return 1;
  }
}

}  // namespace penumbra::bench
