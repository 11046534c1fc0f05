#include "studies.h"

#include <algorithm>
#include <filesystem>

namespace penumbra::bench {

namespace {

// Full runs use each study's defaults (the sizes of its README section); quick ones shrink
// images, maps and frame counts so that the whole suite is a smoke run of a few minutes.
int speedError(const StudyRun& r, std::FILE* out) {
  SpeedErrorOptions o;
  o.backend = r.backend;
  o.outDir = (std::filesystem::path(r.outDir) / "speed-error").string();
  if (r.quick) o.study = "bench/studies/speed-error-quick.json";
  return speedErrorStudy(o, out);
}

int dcs(const StudyRun& r, std::FILE* out) {
  DcsStudyOptions o;
  o.backend = r.backend;
  if (r.quick) o.width = 256, o.height = 256, o.frames = 2;
  return dcsStudies(o, out);
}

int multiview(const StudyRun& r, std::FILE* out) {
  MultiviewOptions o;
  o.backend = r.backend;
  if (r.quick) {
    o.width = 128, o.height = 128, o.map = 512, o.frames = 1;
    o.copies = {1, 2}, o.maps = {8, 24}, o.studies = {1, 2, 5};
  }
  return multiviewStudies(o, out);
}

int singleMap(const StudyRun& r, std::FILE* out) {
  SingleMapOptions o;
  o.backend = r.backend;
  if (r.quick) o.width = 256, o.height = 256, o.map = 1024, o.frames = 2, o.errorSize = 128;
  return singleMapStudies(o, out);
}

int timings(const StudyRun& r, std::FILE* out) {
  TimingOptions o;
  o.backend = r.backend;
  if (r.quick) {
    o.width = 128, o.height = 128, o.samples = {16}, o.frames = 2;
    o.techniques = {"hard-sv", "dcs", "mvr", "vwss", "pcss", "vssm"};
  } else {
    o.width = 256, o.height = 256, o.samples = {16, 64};
    o.techniques = {"hard-sv", "dcs", "mvr", "vwss", "reproject", "pcss", "vssm"};
  }
  return techniqueTimings(o, out);
}

// dcs's raster and compute paths against raytrace, mvr and hard-sv on the engine at
// 256^2 and 512^2, 16 and 64 samples, in one run; the fill and the bound from a profiled frame
// (a later frame, as the timed ones).
int dcsScale(const StudyRun& r, std::FILE* out) {
  const std::string dir = (std::filesystem::path(r.outDir) / "dcs-scale").string();
  std::filesystem::create_directories(dir);
  int rc = 0;
  for (int size : r.quick ? std::vector<int>{128} : std::vector<int>{256, 512}) {
    TimingOptions o;
    o.backend = r.backend;
    o.width = o.height = size;
    o.samples = r.quick ? std::vector<int>{16} : std::vector<int>{16, 64};
    o.frames = r.quick ? 1 : 2;
    o.techniques = {"hard-sv", "mvr"};
    // dcs-4096: the raster path packed by the paper's rule for the partial counts (on the
    // engine base 4096, as every frame was before counters were planned from measured counts), beside the plan for the
    // final counts that `dcs` makes from its second frame on.
    // dcs-one-side-plane: the raster path's wedge solids without the end cones' planes (before
    // the cut wedge solids).
    o.variants = {{"dcs", "dcs", {"path=raster"}, {"profile=true"}},
                  {"dcs-one-side-plane", "dcs", {"path=raster", "end-planes=0"}, {"profile=true"}},
                  {"dcs-4096", "dcs", {"path=raster", "min-base=4096"}, {"profile=true"}},
                  {"dcs-compute", "dcs", {"path=compute"}, {"profile=true"}}};
    o.json = (std::filesystem::path(dir) / ("engine-" + std::to_string(size) + ".json")).string();
    rc = std::max(rc, techniqueTimings(o, out));
  }
  return rc;
}

int shading(const StudyRun& r, std::FILE* out) {
  ShadingStudyOptions o;
  o.backend = r.backend;
  o.outDir = (std::filesystem::path(r.outDir) / "shading").string();
  if (r.quick) o.width = 64, o.frames = 1, o.scenes = {"default", "scenes/glossy.json"};
  // Full: the speed-error study's scenes.
  return shadingStudy(o, out);
}

int lightSize(const StudyRun& r, std::FILE* out) {
  LightSizeOptions o;
  o.backend = r.backend;
  o.outDir = (std::filesystem::path(r.outDir) / "light-size").string();
  if (r.quick) o.width = 64, o.scales = {0.1, 1.0}, o.techniques = {"dcs", "pcss", "smrt"}, o.warmup = 0;
  return lightSizeStudy(o, out);
}

}  // namespace

const std::vector<Study>& studyTable() {
  static const std::vector<Study> table = {
      {"speed-error", "speed against error on the shipped scenes, the headline table and plot", speedError},
      {"dcs", "DCS paper: covered-sample modes, sample counts, shading modes, interleaving, semi-opaque", dcs},
      {"multiview", "VWSS paper tables 1-2, figures 8 and 13, map-resolution convergence", multiview},
      {"single-map", "Sterna table 1, VSSM against PCSS as the light grows, VSSM stages, single-map errors", singleMap},
      {"techniques", "per-stage timings of the main techniques on the engine", timings},
      {"dcs-scale", "dcs raster and compute paths against raytrace, mvr and hard-sv on the engine", dcsScale},
      {"shading", "shading modes (ratio, modulate, per-sample) against the converged shaded reference", shading},
      {"light-size", "error against light size, from near a point to larger than the occluders", lightSize},
  };
  return table;
}

}  // namespace penumbra::bench
