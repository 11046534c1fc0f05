// main() of a standalone study binary (penumbra_bench_<study>): the study's flags parsed into its
// typed options (bench/studies.h), then the same function `penumbra bench` calls. The studies
// that are study files have none: `penumbra study plan/run/merge` runs them. Compiled once
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

}  // namespace

int penumbraBenchMain(const char* study, int argc, char** argv) {
  // Keyed like studyTable() (bench/studies.h).
  static const std::map<std::string, std::function<int(int, char**)>> mains = {
      {"multiview", multiview}, {"single-map", singleMap}, {"shading", shading}};
  return mains.at(study)(argc, argv);
}
