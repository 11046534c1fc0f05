// penumbra's subcommands. Each returns the process exit code (see core/error.h ExitCode).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/flip.h"
#include "pipeline/renderer.h"

namespace penumbra::cli {

struct CommonOptions {
  std::string scene;                   // empty: the built-in default scene
  std::vector<std::string> overrides;  // --set key=value
  std::string backend = "egl";
  std::optional<int> width, height;  // absent: the scene's resolution (-W -1 was read as that: now refused)
  int samples = 16;
  std::string strategy = "stratified";
  std::string pattern = "correlated";
  unsigned seed = 1;
  float time = 0.0f;
  std::string shading = "ratio";
  bool noInterleaveFilter = false;  // --no-interleave-filter
  std::vector<std::string> params;  // --param key=value (technique parameters)
  bool json = false;
};

// `penumbra list [--params] [--format text|markdown|json]`: the techniques, with --params every
// parameter each declares (default, values, meaning); markdown is docs/cli.md's parameter table (without --params,
// README's technique table).
int listTechniques(bool json, bool withParams, const std::string& format, const std::vector<std::string>& names);
int info(const CommonOptions& o);
int render(const CommonOptions& o, const std::string& technique, const std::string& output);
struct CompareCliOptions {
  std::vector<std::string> techniques;  // names or {"all"}
  std::string outDir;                   // empty: out/<scene name>
  std::optional<double> maxError;       // exit 3 above it (visibility RMSE, same-sample reference)
  std::vector<std::string> sweeps, insets;
  bool converged = false;
  int timingFrames = 3, warmup = 1, frames = 1;
  float fps = 30.0f;
  double pixelsPerDegree = kFlipDefaultPixelsPerDegree;  // FLIP's observer
};
// Renders the references and the techniques (CompareOptions) and writes the report
// (compare/report.h) into the output folder.
int compare(const CommonOptions& o, const CompareCliOptions& c);

struct StudyPlanOptions {
  std::string study;   // the study file
  std::string outDir;  // DIR: jobs.jsonl and study.json are written there
};
// `penumbra study plan`: reads and checks the study file (study/study_file.h), expands it into
// jobs (study/plan.h) and writes DIR/jobs.jsonl; prints the counts.
int studyPlan(const StudyPlanOptions& o);

struct StudyRunOptions {
  std::string dir;
  long index = -1;    // --index I (-1: not given)
  std::string shard;  // --shard i/N
  int jobs = 1;       // -j N
  bool force = false, retryFailed = false;
  std::string backend = "egl";
};
// `penumbra study run`: runs the selected jobs of DIR (study/run.h); exit 1 if any of them failed.
int studyRun(const StudyRunOptions& o);
// `penumbra study merge`: DIR's rows into results.jsonl, results.csv and the report
// (study/merge.h); exit 1 if a job failed, 3 if jobs are missing.
int studyMerge(const std::string& dir);

struct BenchOptions {
  std::vector<std::string> studies;  // empty: all (bench/studies.h)
  bool quick = false;
  std::string outDir;  // empty: bench/results/<machine>
  std::string backend = "egl";
};
// Runs the benchmark studies one after another, each writing <outDir>/<study>.txt (the
// speed-error study also its reports and the headline), and <outDir>/machine.txt.
int bench(const BenchOptions& b);

struct LutOptions {
  std::string shape = "rect";  // without a scene: the light shape the table is for (rect | disk)
  int cube = 64, line = 512;   // edge LUT sizes (edge_lut.h)
  std::string outDir = "luts";
  bool ltc = false;  // instead: the LTC GGX table (src/shading/ltc.h) and its error report
  int ltcSize = 64;
};
// --ltc: fits the LTC GGX table, writing <outDir>/ltc_ggx.lut and its per-cell error report
// <outDir>/ltc_ggx_error.csv. Else writes the dcs edge LUT (src/techniques/dcs/edge_lut.h) of the sample pattern the
// options describe: for each rect or disk light of the scene (none given: for a light of --shape), and the luminance
// table (N samples x M sets, RGB EXR) of each textured light.
int lut(const CommonOptions& o, const LutOptions& l);

}  // namespace penumbra::cli
