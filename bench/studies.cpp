#include "studies.h"

#include <filesystem>

namespace penumbra::bench {

namespace {

// A study file's study: bench/studies/<name>.json (quick: <name>-quick.json) into the results
// folder's <name>/.
int fromFile(const std::string& name, const StudyRun& r, std::FILE* out) {
  StudyFileOptions o;
  o.backend = r.backend;
  o.outDir = (std::filesystem::path(r.outDir) / name).string();
  o.study = "bench/studies/" + name + (r.quick ? "-quick" : "") + ".json";
  return studyFile(o, out);
}

int speedError(const StudyRun& r, std::FILE* out) { return fromFile("speed-error", r, out); }
// The DCS paper's studies (parts of one file): covered-sample modes at N = 16 and 64, eq. 3
// against eq. 6, interleaving, semi-opaque occluders against their opaque twin, the memory at
// the paper's Table 1 configuration.
int dcs(const StudyRun& r, std::FILE* out) { return fromFile("dcs", r, out); }
int timings(const StudyRun& r, std::FILE* out) { return fromFile("techniques", r, out); }
// dcs's raster and compute paths (and the raster path without the end cones' planes, and packed
// by the paper's rule for partial counts, min-base=4096) against raytrace, mvr and hard-sv on
// the engine; each dcs path's fill and bound from a profiled frame.
int dcsScale(const StudyRun& r, std::FILE* out) { return fromFile("dcs-scale", r, out); }
int lightSize(const StudyRun& r, std::FILE* out) { return fromFile("light-size", r, out); }

// The VWSS paper's studies (parts): tables 1-2 (the engine instanced 1-6 times, mvr, its layered
// draw, vwss, reproject and pcss-ultra at 24 and 128 maps), figure 13 (buffered against
// unbuffered, compute k = 1, 8, all against the graphics pipeline), figure 8 (the light grown to
// 16x its area at 8 samples per first area; agreement by ring in results.csv), and the maps'
// resolution.
int multiview(const StudyRun& r, std::FILE* out) { return fromFile("multiview", r, out); }
// Sterna's table 1 (the shadow-mask passes, checkerboarding), the single-map methods as the
// light grows (the light-size curves), VSSM's stages by map size, and their errors on the shipped
// scenes and hard cases against both references.
int singleMap(const StudyRun& r, std::FILE* out) { return fromFile("single-map", r, out); }

int shading(const StudyRun& r, std::FILE* out) {
  ShadingStudyOptions o;
  o.backend = r.backend;
  o.outDir = (std::filesystem::path(r.outDir) / "shading").string();
  if (r.quick) o.width = 64, o.frames = 1, o.scenes = {"default", "scenes/glossy.json"};
  // Full: the speed-error study's scenes.
  return shadingStudy(o, out);
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
