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

// Speed against error on the shipped scenes but the bunny crowd (bench_speed_error.cpp): a study
// file (docs/studies.md) planned, run and merged into outDir, its per-scene reports and the
// cross-scene headline.
struct SpeedErrorOptions {
  std::string study = "bench/studies/speed-error.json";
  std::string outDir;  // required: the study's folder
  gl::Backend backend = gl::Backend::Egl;
};
int speedErrorStudy(const SpeedErrorOptions& o, std::FILE* out);

// DCS paper studies (bench_dcs.cpp): covered-sample modes, sample counts, shading, interleaving,
// semi-opaque occluders.
struct DcsStudyOptions {
  std::string scene = "scenes/stained-glass.json";  // modes, sample counts, shading, interleaving
  std::string semi = "scenes/semi-opaque.json";     // semi-opaque occluders (its opaque twin made in memory)
  int width = 512, height = 512, frames = 5, warmup = 1;
  std::string json;  // results as JSON here, if given
  gl::Backend backend = gl::Backend::Egl;
};
int dcsStudies(const DcsStudyOptions& o, std::FILE* out);

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

// A technique with parameters, timed under its own label; `profile`: its statistics come from
// one more, untimed frame with these parameters added (dcs `profile=true`: counters that slow it).
struct TimedVariant {
  std::string label, technique;
  std::vector<std::string> params, profile;
};

// Per-stage timings of chosen techniques and sample counts (bench_techniques.cpp).
struct TimingOptions {
  std::string scene = "scenes/engine.json";
  int width = 512, height = 512, frames = 5, warmup = 1;
  std::vector<int> samples = {1};
  std::vector<std::string> techniques = {"hard-sv"};
  std::vector<TimedVariant> variants;  // timed after `techniques`, before raytrace
  PixelPattern pattern = PixelPattern::Correlated;
  ShadingMode shading = ShadingMode::Modulate;  // eq. 3, as the README's timing tables were measured
  std::string json;                             // results as JSON here, if given
  gl::Backend backend = gl::Backend::Egl;
};
int techniqueTimings(const TimingOptions& o, std::FILE* out);

// Shading modes against the converged shaded reference on every shipped scene (bench_shading.cpp):
// ratio, modulate and per-sample, their error and their cost per frame.
struct ShadingStudyOptions {
  // Empty: the speed-error study's scenes (every shipped scene, the glossy one's
  // metallic-roughness materials among them), read from its study file.
  std::vector<std::string> scenes;
  std::string technique = "dcs";
  int samples = 16;
  int width = 128;  // height: the scene's aspect
  int frames = 3, warmup = 1;
  std::string outDir;  // shading.json here, if given
  gl::Backend backend = gl::Backend::Egl;
};
int shadingStudy(const ShadingStudyOptions& o, std::FILE* out);

// Error against light size (bench_light_size.cpp): each scene's lights scaled from near a point to
// larger than its occluders, every technique against the same-sample reference at each size; a
// chart and a table per scene. The scenes: occluders that overlap from the light centre (hard case
// 15's offset plates), contact (16: a box on the floor, a plate over a plate) and a thin occluder
// far above its receiver (23).
struct LightSizeOptions {
  std::vector<std::string> scenes = {"scenes/hard/15-two-plates.json", "scenes/hard/16-contact.json",
                                     "scenes/hard/23-analytic-square.json"};
  std::vector<double> scales = {0.05, 0.1, 0.25, 0.5, 1.0, 1.5, 2.0};
  std::vector<std::string> techniques = {
      "hard-sv", "dcs",      "mvr",  "vwss", "pcss",           "pcss-ultra",   "pcss-contact",
      "vssm",    "msm-soft", "evsm", "smrt", "smrt-unclamped", "smrt-contact", "raytrace-denoised"};
  int samples = 16;
  int width = 128;  // height: the scene's aspect
  int frames = 1, warmup = 1;
  bool images = false;  // each size's PNG images (false: reports and plots only)
  std::string outDir;   // required
  gl::Backend backend = gl::Backend::Egl;
};
int lightSizeStudy(const LightSizeOptions& o, std::FILE* out);

// What `penumbra bench` gives every study.
struct StudyRun {
  gl::Backend backend = gl::Backend::Egl;
  bool quick = false;
  std::string outDir;  // the machine's results folder (the speed-error study writes under it)
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
