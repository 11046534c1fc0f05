// penumbra: headless soft-shadow renderer. Subcommands: list, info, render, compare, lut, bench.
// Exit codes: 0 ok, 1 error, 2 usage, 3 compare --max-error exceeded, 77 no GL context.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <new>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/files.h"
#include "core/log.h"
#include "core/memory.h"

using namespace penumbra;

namespace {

// Each subcommand takes only the options it uses (`penumbra lut --shading ratio` is a usage
// error), in groups: the scene, the light samples, the rendering.
enum class Options { Scene = 1, Samples = 2, Rendering = 4 };
constexpr int operator|(Options a, Options b) { return int(a) | int(b); }

void addOptions(CLI::App* app, cli::CommonOptions& o, int groups) {
  app->add_option("scene", o.scene, "scene file (.json, .gltf, .glb, .obj, .ply, .off, .stl); none: built-in default");
  app->add_option("--set", o.overrides, "override a scene key: key=value (repeatable)");
  app->add_flag("--json", o.json, "machine-readable output on stdout");
  if (groups & int(Options::Samples)) {
    auto* g = app->add_option_group("light samples");
    g->add_option("--samples", o.samples, "light samples per light, for every technique and the reference")
        ->capture_default_str();
    g->add_option("--strategy", o.strategy, "sample strategy: " + namesOf(kSampleStrategyNames))->capture_default_str();
    g->add_option("--pattern", o.pattern, "per-pixel sets: " + namesOf(kPixelPatternNames))->capture_default_str();
    g->add_option("--seed", o.seed, "sample seed")->capture_default_str();
    g->add_option("--time", o.time, "animation time in seconds (animated textured lights)")->capture_default_str();
  }
  if (groups & int(Options::Rendering)) {
    auto* g = app->add_option_group("rendering");
    g->add_option("--param", o.params,
                  "technique parameter key=value (repeatable; `penumbra list --params`, e.g. map=512)");
    g->add_option("--backend", o.backend, "GL backend: " + namesOf(gl::kBackendNames))->capture_default_str();
    g->add_option("-W,--width", o.width, "image width (default: the scene's)");
    g->add_option("-H,--height", o.height, "image height (default: the scene's)");
    g->add_option("--shading", o.shading,
                  "ratio (unshadowed term x shadow ratio, Heitz et al. 2018) | ratio-exact (the unshadowed term "
                  "integrated on the CPU, not the LTC) | modulate (DCS eq. 3) | per-sample (eq. 6)")
        ->capture_default_str();
    g->add_flag("--no-interleave-filter", o.noInterleaveFilter,
                "with --pattern interleaved: skip the normal/depth-aware gather of the K x K sets");
  }
}

}  // namespace

int main(int argc, char** argv) {
  setLogLevel("info");
  CLI::App app{"penumbra: soft shadows from area lights, measured against a ray-traced reference"};
  app.require_subcommand(1);
  std::string logLevel = "info";
  // spdlog reads an unknown level as "off": refuse it instead of silencing every message.
  app.add_option("--log", logLevel, "log level: trace, debug, info, warn, error, off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
  std::string memoryBudget;
  app.add_option("--memory-budget", memoryBudget,
                 "the most memory this run may hold, e.g. 4GiB (default: physical memory and ulimit); "
                 "a scene, texture or technique needing more is refused before it allocates");
  // Subcommands made below inherit this: an option of the main command (--log) is accepted
  // after the subcommand too (`penumbra render --log debug`), as README lists it.
  app.fallthrough();

  cli::CommonOptions o;
  bool listJson = false, listParams = false;
  std::string listFormat = "text";
  auto* list = app.add_subcommand("list", "list the techniques, one line each");
  list->add_flag("--json", listJson, "machine-readable output (as --format json)");
  list->add_flag("--params", listParams, "every technique's parameters (--param key=value): default, values, meaning");
  list->add_option("--format", listFormat,
                   "text, markdown (README's technique table; with --params docs/cli.md's parameter table) or json")
      ->capture_default_str();
  std::vector<std::string> listNames;
  list->add_option("techniques", listNames, "only these techniques (a technique folder's README.md lists its own)");

  auto* info = app.add_subcommand("info", "print a scene's triangle and light counts and mesh reports");
  addOptions(info, o, int(Options::Scene));

  std::string technique = "hard-sv", output;
  auto* render = app.add_subcommand("render", "render one technique");
  addOptions(render, o, Options::Samples | Options::Rendering);
  render->add_option("-t,--technique", technique, "technique (see `penumbra list`)")->capture_default_str();
  render->add_option("-o,--output", output, "output image (.exr: float RGB + visibility layers; .png: sRGB)")
      ->required();

  std::string techniques = "all";
  cli::CompareCliOptions cmp;
  auto* compare = app.add_subcommand("compare",
                                     "render techniques and the raytrace reference with the same samples; write "
                                     "index.html, report.json/.csv, plot.svg, images");
  addOptions(compare, o, Options::Samples | Options::Rendering);
  compare->add_option("--techniques", techniques, "comma-separated techniques, or 'all'")->capture_default_str();
  compare->add_option("-o,--output", cmp.outDir, "output folder (default: out/<scene name>)");
  double maxError = 0.0;
  auto* maxErrorOption = compare->add_option(
      "--max-error", maxError, "exit 3 if a technique's visibility RMSE against the reference exceeds this");
  compare->add_option(
      "--sweep", cmp.sweeps,
      "key=v1,v2,...: samples, resolution or a technique parameter (repeatable; presets are the product)");
  compare->add_flag("--converged", cmp.converged,
                    "also measure against raytrace-converged (implied by a samples sweep)");
  compare->add_option("--inset", cmp.insets,
                      "x,y,w,h: a region to zoom in the report (repeatable; default: two chosen)");
  compare->add_option("--timing-frames", cmp.timingFrames, "timed frames per technique (median and spread)")
      ->capture_default_str();
  compare->add_option("--warmup", cmp.warmup, "untimed frames first")->capture_default_str();
  compare->add_option("--frames", cmp.frames, "frames of the scene's animation, for temporal flicker")
      ->capture_default_str();
  compare->add_option("--fps", cmp.fps, "frames per second of --frames")->capture_default_str();
  compare
      ->add_option("--ppd", cmp.pixelsPerDegree,
                   "FLIP's pixels per degree (default: 0.7 m from a 0.7 m wide 3840-pixel monitor, the FLIP paper's)")
      ->capture_default_str();

  cli::BenchOptions benchOptions;
  auto* bench =
      app.add_subcommand("bench", "run the benchmark studies; tables, reports and plots into bench/results/<machine>/");
  bench->add_option("--studies", benchOptions.studies, "comma-separated studies (default: all; docs/benchmarks.md)")
      ->delimiter(',');
  bench->add_flag("--quick", benchOptions.quick, "smaller images, maps and frame counts (a smoke run)");
  bench->add_option("-o,--output", benchOptions.outDir, "output folder (default: bench/results/<machine>)");
  bench->add_option("--backend", benchOptions.backend, "GL backend: " + namesOf(gl::kBackendNames))
      ->capture_default_str();

  cli::StudyPlanOptions planOptions;
  auto* study = app.add_subcommand(
      "study", "studies as data: plan a study file into jobs, run them, merge their rows (docs/studies.md)");
  study->require_subcommand(1);
  auto* plan = study->add_subcommand("plan", "expand a study file into DIR/jobs.jsonl, one row per unit of work");
  plan->add_option("study", planOptions.study, "the study file (JSON)")->required();
  plan->add_option("-o,--output", planOptions.outDir, "the study's folder")->required();
  cli::StudyRunOptions runOptions;
  auto* run = study->add_subcommand("run", "run a planned study's jobs (all, one, or a shard), skipping those done");
  run->add_option("dir", runOptions.dir, "the study's folder (DIR/jobs.jsonl)")->required();
  run->add_option("--index", runOptions.index, "run the job on this line of jobs.jsonl (from 0): a Slurm array task");
  run->add_option("--shard", runOptions.shard, "i/N: run the jobs whose index modulo N is i");
  run->add_option("-j,--jobs", runOptions.jobs, "processes at once")->capture_default_str();
  run->add_flag("--force", runOptions.force, "redo the selected jobs even where their rows exist");
  run->add_flag("--retry-failed", runOptions.retryFailed, "redo the selected jobs whose rows say they failed");
  run->add_option("--backend", runOptions.backend, "GL backend: " + namesOf(gl::kBackendNames))->capture_default_str();
  std::string mergeDir;
  auto* merge = study->add_subcommand("merge", "merge the jobs' rows: results.jsonl, results.csv and the report");
  merge->add_option("dir", mergeDir, "the study's folder")->required();

  cli::LutOptions lutOptions;
  auto* lut = app.add_subcommand(
      "lut",
      "write the dcs edge LUT of a sample pattern (and textured lights' luminance tables), or the LTC GGX table");
  addOptions(lut, o, int(Options::Samples));
  lut->add_option("--shape", lutOptions.shape, "light shape when no scene is given: rect | disk")
      ->capture_default_str();
  lut->add_option("--cube", lutOptions.cube, "sector table size (cube map faces)")->capture_default_str();
  lut->add_option("--line", lutOptions.line, "line table size")->capture_default_str();
  lut->add_option("-o,--output", lutOptions.outDir, "output folder")->capture_default_str();
  lut->add_flag("--ltc", lutOptions.ltc, "fit the LTC GGX table instead (ltc_ggx.lut and ltc_ggx_error.csv)");
  lut->add_option("--ltc-size", lutOptions.ltcSize, "LTC table size (cells a side)")->capture_default_str();

  cli::requireDecimalNumbers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "penumbra: %s\n", e.what());
    return int(ExitCode::Usage);
  }
  setLogLevel(logLevel);
  installInterruptCleanup();  // Ctrl-C leaves no .partial-<pid> file behind

  try {
    if (!memoryBudget.empty()) setMemoryBudget(cli::parseByteSize("--memory-budget", memoryBudget));
    if (*list) return cli::listTechniques(listJson, listParams, listFormat, listNames);
    if (*info) return cli::info(o);
    if (*render) return cli::render(o, technique, output);
    if (*lut) return cli::lut(o, lutOptions);
    if (*bench) return cli::bench(benchOptions);
    if (*plan) return cli::studyPlan(planOptions);
    if (*run) return cli::studyRun(runOptions);
    if (*merge) return cli::studyMerge(mergeDir);
    if (*compare) {
      std::vector<std::string> names;
      std::string cur;
      for (char c : techniques + ",") {
        if (c == ',') {
          if (!cur.empty()) names.push_back(cur);
          cur.clear();
        } else {
          cur += c;
        }
      }
      cmp.techniques = names;
      if (maxErrorOption->count()) cmp.maxError = maxError;
      return cli::compare(o, cmp);
    }
  } catch (const Error& e) {
    // A field the libraries name is shown as the flag that sets it.
    const std::string command = app.get_subcommands().empty() ? "" : app.get_subcommands().front()->get_name();
    const std::string flag = cli::flagFor(e.where(), command);
    std::fprintf(stderr, "penumbra: %s\n", flag.empty() ? e.what() : Error(flag, e.detail()).what());
    return int(e.exitCode());
  } catch (const std::bad_alloc&) {
    // What the up-front estimates (core/memory.h) did not foresee: still one line, exit 1.
    std::fprintf(stderr,
                 "penumbra: out of memory: the scene, image or technique needs more memory "
                 "than this process may allocate (physical memory or ulimit)\n");
    return int(ExitCode::Error);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "penumbra: %s\n", e.what());
    return int(ExitCode::Error);
  }
  return int(ExitCode::Usage);
}
