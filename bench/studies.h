// The benchmark studies. One table (studyTable) lists them with the settings of `penumbra bench`
// (full: bench/studies/<name>.json; quick: <name>-quick.json, smaller sizes, fewer frames). All
// but one are study files run through study/ (plan, run, merge); the shading study is a function
// taking its typed options and writing its table to `out`, also a standalone binary
// (penumbra_bench_shading, src/cli/bench_main.cpp). `penumbra bench` (src/cli/commands.cpp)
// writes bench/results/<machine>/.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "gl/context.h"
#include "pipeline/renderer.h"

namespace penumbra::bench {

// A study file (docs/studies.md, bench/studies/<name>.json) planned, run and merged into
// outDir (bench_study_file.cpp); its tables are the merge's (report/headline.md, stages.md,
// light-size.md and a report per scene). A run into a folder that holds an earlier run of the same build renders
// only what is missing; job folders of other plans there are removed.
struct StudyFileOptions {
  std::string study;   // required: the study file
  std::string outDir;  // required: the study's folder
  gl::Backend backend = gl::Backend::Egl;
};
int studyFile(const StudyFileOptions& o, std::FILE* out);

// Shading modes against the converged shaded reference on every shipped scene (bench_shading.cpp):
// ratio, modulate and per-sample, their error and their cost per frame.
struct ShadingStudyOptions {
  // Empty: the speed-error study's scenes (every shipped scene, the glossy one's
  // metallic-roughness materials among them), read from bench/studies/speed-error.json.
  std::vector<std::string> scenes;
  std::string technique = "dcs";
  int samples = 16;
  int width = 128;  // height: the scene's aspect
  int frames = 3, warmup = 1;
  std::string outDir;  // shading.json here, if given
  gl::Backend backend = gl::Backend::Egl;
};
int shadingStudy(const ShadingStudyOptions& o, std::FILE* out);

// What `penumbra bench` gives every study.
struct StudyRun {
  gl::Backend backend = gl::Backend::Egl;
  bool quick = false;
  std::string outDir;  // the machine's results folder (a study file's study writes its folder under it)
};

struct Study {
  std::string name;         // "speed-error", "dcs", ...
  std::string description;  // one line
  // Runs the study with the settings of `penumbra bench` (or `--quick`).
  int (*run)(const StudyRun& run, std::FILE* out);
};
// The explicit table of studies, in the order `penumbra bench` runs them.
const std::vector<Study>& studyTable();

}  // namespace penumbra::bench
