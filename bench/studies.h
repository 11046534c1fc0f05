// The benchmark studies, each a function taking its typed options and writing its tables to
// `out`. One table (studyTable) lists them with the settings of `penumbra bench` (full: each
// study's defaults, the sizes of its README section; quick: smaller sizes, fewer frames); the
// standalone binaries (penumbra_bench_<study>, src/cli/bench_main.cpp) parse their flags into
// the same options and call the same functions. `penumbra bench` (src/cli/commands.cpp) writes
// bench/results/<machine>/.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "gl/context.h"
#include "pipeline/renderer.h"

namespace penumbra::bench {

// A study file (docs/studies.md, bench/studies/<name>.json) planned, run and merged into
// outDir (bench_study_file.cpp): speed-error, dcs, techniques, dcs-scale and light-size are
// such files; their tables are the merge's (report/headline.md, stages.md, light-size.md and a
// report per scene). A run into a folder that holds an earlier run of the same build renders
// only what is missing; job folders of other plans there are removed.
struct StudyFileOptions {
  std::string study;   // required: the study file
  std::string outDir;  // required: the study's folder
  gl::Backend backend = gl::Backend::Egl;
};
int studyFile(const StudyFileOptions& o, std::FILE* out);

// VWSS paper tables 1-2, figures 8 and 13, map-resolution convergence (bench_multiview.cpp).
struct MultiviewOptions {
  std::string scene = "scenes/engine.json";  // base scene: the floor then the occluders to instance
  int width = 256, height = 256;
  int map = 1024;  // depth-map resolution of studies 1-4
  int frames = 3, warmup = 1;
  std::vector<int> copies = {1, 2, 5, 6};  // instances of the occluders per scene of study 1
  float spacing = 1.6f;                    // distance between instances
  std::vector<int> maps = {24, 128};       // light samples (maps) of study 1
  std::vector<int> studies = {1, 2, 3, 4, 5};
  gl::Backend backend = gl::Backend::Egl;
};
int multiviewStudies(const MultiviewOptions& o, std::FILE* out);

// Sterna's table 1, VSSM against PCSS, VSSM stages, single-map errors (bench_pcss.cpp).
struct SingleMapOptions {
  std::string scene = "scenes/stained-glass.json";
  int width = 512, height = 512, map = 2048;
  int samples = 16;  // light samples of the reference (pcss's horizon weights)
  int frames = 5, warmup = 1;
  int errorSize = 256;  // image size of study 4
  gl::Backend backend = gl::Backend::Egl;
};
int singleMapStudies(const SingleMapOptions& o, std::FILE* out);

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
