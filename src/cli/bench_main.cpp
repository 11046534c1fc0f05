// main() of a standalone study binary (penumbra_bench_<study>): the study's flags parsed into its
// typed options (bench/studies.h), then the same function `penumbra bench` calls. Compiled once
// (CLI11 makes it a slow unit) for all of them: each binary's main() is one generated line that
// names its study (src/cli/CMakeLists.txt).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <functional>
#include <map>
#include <string>

#include "cli/options.h"
#include "core/error.h"
#include "studies.h"

using namespace penumbra;
using namespace penumbra::bench;

namespace {

// --backend, the flags of `app` (`typed`: those that are strings to the typed options), then the
// study: one line on stderr and its exit code for an Error.
template <class Options>
int runStudy(CLI::App& app, int argc, char** argv, Options& o, int (*study)(const Options&, std::FILE*),
             const std::function<void()>& typed = {}) {
  std::string backend = "egl";
  app.add_option("--backend", backend, "GL backend: egl | osmesa");
  cli::requireDecimalNumbers(app);
  CLI11_PARSE(app, argc, argv);
  try {
    o.backend = cli::parseBackend(backend);
    if (typed) typed();
    return study(o, stdout);
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: %s\n", app.get_name().c_str(), e.what());
    return int(e.exitCode());
  }
}

int speedError(int argc, char** argv) {
  CLI::App app{"speed against error on the shipped scenes: a study file planned, run and merged",
               "penumbra_bench_speed_error"};
  SpeedErrorOptions o;
  app.add_option("--study", o.study, "the study file (docs/studies.md)")->capture_default_str();
  app.add_option("-o", o.outDir, "the study's folder")->required();
  return runStudy(app, argc, argv, o, speedErrorStudy);
}

int dcs(int argc, char** argv) {
  CLI::App app{"the DCS paper's studies in one run", "penumbra_bench_dcs"};
  DcsStudyOptions o;
  app.add_option("scene", o.scene, "scene for the mode, sample-count, shading and interleaving studies");
  app.add_option("--semi", o.semi, "scene with semi-opaque occluders (its opaque twin is made in memory)");
  app.add_option("-W", o.width);
  app.add_option("-H", o.height);
  app.add_option("--frames", o.frames);
  app.add_option("--warmup", o.warmup);
  app.add_option("--json", o.json);
  return runStudy(app, argc, argv, o, dcsStudies);
}

int multiview(int argc, char** argv) {
  CLI::App app{"the multi-view shadow-map studies in one run", "penumbra_bench_multiview"};
  MultiviewOptions o;
  app.add_option("scene", o.scene, "base scene: the floor then the occluders to instance");
  app.add_option("-W", o.width);
  app.add_option("-H", o.height);
  app.add_option("--map", o.map, "depth-map resolution of studies 1-4");
  app.add_option("--frames", o.frames);
  app.add_option("--warmup", o.warmup);
  app.add_option("--copies", o.copies, "instances of the occluders per scene of study 1")->delimiter(',');
  app.add_option("--spacing", o.spacing, "distance between instances");
  app.add_option("--maps", o.maps, "light samples (maps) of study 1")->delimiter(',');
  app.add_option("--study", o.studies, "studies to run")->delimiter(',');
  return runStudy(app, argc, argv, o, multiviewStudies);
}

int singleMap(int argc, char** argv) {
  CLI::App app{"the single-map (pcss, vssm) studies in one run", "penumbra_bench_pcss"};
  SingleMapOptions o;
  app.add_option("scene", o.scene);
  app.add_option("-W", o.width);
  app.add_option("-H", o.height);
  app.add_option("--map", o.map);
  app.add_option("--samples", o.samples, "light samples of the reference (pcss's horizon weights)");
  app.add_option("--frames", o.frames);
  app.add_option("--warmup", o.warmup);
  app.add_option("--error-size", o.errorSize, "image size of study 4");
  return runStudy(app, argc, argv, o, singleMapStudies);
}

int timings(int argc, char** argv) {
  CLI::App app{"per-stage timing of techniques against raytrace", "penumbra_bench"};
  TimingOptions o;
  std::string pattern = "correlated", shading = "modulate";
  app.add_option("scene", o.scene);
  app.add_option("-W", o.width);
  app.add_option("-H", o.height);
  app.add_option("--samples", o.samples)->delimiter(',');
  app.add_option("--techniques", o.techniques)->delimiter(',');
  app.add_option("--frames", o.frames);
  app.add_option("--warmup", o.warmup);
  app.add_option("--json", o.json);
  app.add_option("--pattern", pattern, "correlated | decorrelated | interleaved");
  app.add_option("--shading", shading, "modulate (eq. 3) | per-sample (eq. 6) | ratio");
  return runStudy(app, argc, argv, o, techniqueTimings, [&] {
    o.pattern = cli::parsePixelPattern(pattern);
    o.shading = cli::parseShadingMode(shading);
  });
}

int shading(int argc, char** argv) {
  CLI::App app{"shading modes against the converged shaded reference", "penumbra_bench_shading"};
  ShadingStudyOptions o;
  app.add_option("--scenes", o.scenes, "scene files ('default': the built-in scene; default: speed-error's)")
      ->delimiter(',');
  app.add_option("--technique", o.technique);
  app.add_option("--samples", o.samples);
  app.add_option("-W", o.width, "image width (height: the scene's aspect)");
  app.add_option("--frames", o.frames);
  app.add_option("--warmup", o.warmup);
  app.add_option("-o", o.outDir, "output folder (shading.json)");
  return runStudy(app, argc, argv, o, shadingStudy);
}

int lightSize(int argc, char** argv) {
  CLI::App app{"error against light size", "penumbra_bench_light_size"};
  LightSizeOptions o;
  app.add_option("--scenes", o.scenes, "scene files")->delimiter(',');
  app.add_option("--scales", o.scales, "light scales (comma-separated)")->delimiter(',');
  app.add_option("--techniques", o.techniques)->delimiter(',');
  app.add_option("--samples", o.samples);
  app.add_option("-W", o.width, "image width (height: the scene's aspect)");
  app.add_option("--frames", o.frames, "timed frames per technique and size");
  app.add_option("--warmup", o.warmup);
  app.add_option("--images", o.images, "write each size's PNG images (0: reports and plots only)");
  app.add_option("-o", o.outDir, "output folder")->required();
  return runStudy(app, argc, argv, o, lightSizeStudy);
}

}  // namespace

int penumbraBenchMain(const char* study, int argc, char** argv) {
  // Keyed like studyTable() (bench/studies.h).
  static const std::map<std::string, std::function<int(int, char**)>> mains = {
      {"speed-error", speedError}, {"dcs", dcs},         {"multiview", multiview}, {"single-map", singleMap},
      {"techniques", timings},     {"shading", shading}, {"light-size", lightSize}};
  return mains.at(study)(argc, argv);
}
