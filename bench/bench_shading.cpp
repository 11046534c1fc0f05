// Benchmark (not a test) of the shading modes: on every shipped scene, one technique
// (dcs, whose per-sample results equal ray tracing) shaded with `ratio` (Heitz, Hill and McGuire
// 2018), `modulate` (DCS eq. 3) and `per-sample` (eq. 6), each image's RMSE against the
// converged shaded reference (raytrace-converged: the same BRDF, 1024 stratified samples per
// pixel) relative to that reference's mean radiance, and each mode's frame
// and shading-stage time (median of the timed frames after warm-up, one run, one machine).
//
//   penumbra_bench_shading [--scenes a.json,b.json] [-W 128] [--samples 16] [--frames 3]
//                          [--backend egl] [-o FOLDER]
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "bench_common.h"
#include "studies.h"
#include "study/study_file.h"
#include "core/error.h"
#include "core/files.h"
#include "core/log.h"
#include "core/metrics.h"
#include "gl/context.h"
#include "pipeline/renderer.h"
#include "scene/scene.h"

namespace penumbra::bench {

namespace {

Scene loadStudyScene(const std::string& path) { return path == "default" ? defaultScene() : loadScene(path); }

// Mean of `im` over the pixels `valid` marks (every channel).
double meanOver(const Image& im, const std::vector<std::uint8_t>& valid) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < im.pixelCount(); ++i) {
    if (!valid.empty() && !valid[i]) continue;
    for (int c = 0; c < im.channels; ++c) sum += im.data[i * std::size_t(im.channels) + std::size_t(c)];
    n += std::size_t(im.channels);
  }
  return n ? sum / double(n) : 0.0;
}

}  // namespace

int shadingStudy(const ShadingStudyOptions& o, std::FILE* out) {
  setLogLevel("warn");
  const ShadingMode modes[3] = {ShadingMode::Ratio, ShadingMode::Modulate, ShadingMode::PerSample};
  try {
    auto ctx = gl::Context::create(o.backend);
    nlohmann::json results;
    results["renderer"] = ctx->renderer();
    results["technique"] = o.technique, results["samples"] = o.samples, results["width"] = o.width;
    results["frames"] = o.frames, results["warmup"] = o.warmup, results["date"] = utcNow();
    std::fprintf(out,
                 "Shading modes: %s, N = %d, width %d, median of %d frames after %d warm-up, renderer %s\n"
                 "shaded RMSE against raytrace-converged (1024 samples, same BRDF) / its mean radiance; ms per frame "
                 "(shading stage)\n",
                 o.technique.c_str(), o.samples, o.width, o.frames, o.warmup, ctx->renderer().c_str());
    std::fprintf(out, "  %-32s %10s %10s %10s   %16s %16s %16s\n", "scene", "ratio", "modulate", "per-sample",
                 "ratio ms", "modulate ms", "per-sample ms");
    std::map<ShadingMode, double> errorSum, msSum, shadingSum;
    int scenes = 0, failures = 0;
    std::vector<std::string> paths = o.scenes;
    if (paths.empty())
      for (const study::SceneEntry& e : study::readStudy("bench/studies/speed-error.json").allScenes())
        paths.push_back(e.path);
    for (const std::string& path : paths) {
      try {
        Scene scene = loadStudyScene(path);
        RenderSettings s;
        s.width = o.width;
        s.height = std::max(1, int(std::lround(double(o.width) * scene.height / scene.width)));
        s.sampling.count = o.samples;
        s.gbufferResults = true;
        Renderer reference(*ctx, scene, s);
        auto converged = makeTechnique("raytrace-converged");
        const FrameResult truth = reference.render(*converged, "raytrace-converged");
        const double mean = meanOver(truth.color, truth.gbuffer.valid);
        if (!(mean > 0.0)) throw Error(path, "the converged reference is black: nothing to measure");
        std::map<ShadingMode, double> error;
        std::map<ShadingMode, Timing> time;
        for (ShadingMode m : modes) {
          RenderSettings sm = s;
          sm.shading = m;
          Renderer r(*ctx, scene, sm);
          auto tech = makeTechnique(o.technique);
          time.emplace(m, timeFrames(r, *tech, o.frames, o.warmup));
          error[m] = compareImages(time.at(m).last.color, truth.color, {}, truth.gbuffer.valid).rmse / mean;
        }
        std::fprintf(out, "  %-32s %10.4f %10.4f %10.4f   %9.1f (%4.1f) %9.1f (%4.1f) %9.1f (%4.1f)\n", path.c_str(),
                     error[modes[0]], error[modes[1]], error[modes[2]], time.at(modes[0]).total.median,
                     time.at(modes[0]).stage("shading"), time.at(modes[1]).total.median,
                     time.at(modes[1]).stage("shading"), time.at(modes[2]).total.median,
                     time.at(modes[2]).stage("shading"));
        nlohmann::json row = {{"scene", path}, {"meanRadiance", mean}};
        for (ShadingMode m : modes) {
          row[toString(m)] = {{"relativeRmse", error[m]},
                              {"totalMs", time.at(m).total.median},
                              {"totalMinMs", time.at(m).total.min},
                              {"totalMaxMs", time.at(m).total.max},
                              {"shadingMs", time.at(m).stage("shading")}};
          errorSum[m] += error[m], msSum[m] += time.at(m).total.median, shadingSum[m] += time.at(m).stage("shading");
        }
        results["scenes"].push_back(row);
        ++scenes;
      } catch (const std::exception& e) {
        // One scene's failure is its row; the others go on (and the study exits 1).
        std::fprintf(out, "  %-32s failed: %s\n", path.c_str(), e.what());
        results["scenes"].push_back({{"scene", path}, {"failed", e.what()}});
        ++failures;
      }
    }
    if (scenes > 0) {
      std::fprintf(out, "  %-32s %10.4f %10.4f %10.4f   %9.1f (%4.1f) %9.1f (%4.1f) %9.1f (%4.1f)\n",
                   ("mean of " + std::to_string(scenes) + " scenes").c_str(), errorSum[modes[0]] / scenes,
                   errorSum[modes[1]] / scenes, errorSum[modes[2]] / scenes, msSum[modes[0]] / scenes,
                   shadingSum[modes[0]] / scenes, msSum[modes[1]] / scenes, shadingSum[modes[1]] / scenes,
                   msSum[modes[2]] / scenes, shadingSum[modes[2]] / scenes);
      const ShadingMode best = *std::min_element(
          std::begin(modes), std::end(modes), [&](ShadingMode a, ShadingMode b) { return errorSum[a] < errorSum[b]; });
      std::fprintf(out,
                   "  lowest mean error: %s; ratio / modulate frame time %.3f, shading stage %.2f ms against %.2f ms\n",
                   toString(best), msSum[modes[0]] / msSum[modes[1]], shadingSum[modes[0]] / scenes,
                   shadingSum[modes[1]] / scenes);
      for (ShadingMode m : modes)
        results["mean"][toString(m)] = {{"relativeRmse", errorSum[m] / scenes},
                                        {"totalMs", msSum[m] / scenes},
                                        {"shadingMs", shadingSum[m] / scenes}};
      results["lowestMeanError"] = toString(best);
    }
    if (!o.outDir.empty()) {
      std::filesystem::create_directories(o.outDir);
      writeTextFile((std::filesystem::path(o.outDir) / "shading.json").string(), results.dump(2) + "\n");
    }
    return failures > 0 ? 1 : 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "penumbra_bench_shading: %s\n", e.what());
    return int(e.exitCode());
  }
}

}  // namespace penumbra::bench
