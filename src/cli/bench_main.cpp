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
  static const std::map<std::string, std::function<int(int, char**)>> mains = {{"shading", shading}};
  return mains.at(study)(argc, argv);
}
