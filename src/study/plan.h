// A study's plan: one row per unit of work, `DIR/jobs.jsonl` (docs/studies.md). A job is a
// technique at one configuration (scene, parameters, light samples, size, seed, strategy) or a
// reference: the same-sample reference of a configuration (shared by every technique job of it)
// or the converged reference of a scene and size. A job's id is stable: a hash of its row, of the
// content of every file it reads (the scene file and what it names: meshes, glTF buffers,
// textures) and of the penumbra build, so that a job is redone exactly when something it depends
// on changed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/study_file.h"

namespace penumbra::study {

struct Job {
  std::string id;                    // 16 hex digits
  std::string kind;                  // "technique", "reference" (same samples) or "converged"
  std::string scene;                 // a path, or "default"
  std::vector<std::string> variant;  // SceneEntry::variant: the scene changed in memory
  std::string technique;             // kind technique: its name; references: "raytrace" / "raytrace-converged"
  std::vector<std::string> params;
  int samples = 0;  // light samples a pixel (converged: the reference's own)
  Size size;
  std::uint32_t seed = 0;
  std::string strategy;
  double lightScale = 1.0;             // every light's extent times this
  std::string shading = "ratio";       // kShadingModeNames
  std::string pattern = "correlated";  // kPixelPatternNames
  std::vector<std::string> profile;    // TechniqueAxis::profile
  int frames = 1, warmup = 0;
  std::string images = "all";  // StudySpec::images
  std::string reference;       // technique jobs: the id of their same-sample reference
  std::string converged;       // technique and reference jobs with a converged reference: its id

  // The row (keys of the axes a study leaves at their defaults are left out: variant,
  // lightScale, shading, pattern, profile).
  nlohmann::json json() const;
  // A row of jobs.jsonl read back; `where` ("DIR/jobs.jsonl:12") names it in errors.
  static Job fromJson(const nlohmann::json& row, const std::string& where);
};

// The files a scene reads, its own first, then every file its text names that exists (relative
// to its folder): meshes and textures of a scene file, a glTF's buffers and images, an OBJ's
// material library. "default" reads none.
std::vector<std::string> sceneInputs(const std::string& scene);

// The jobs of a study, references first (a study of parts: each part's, in order, a job two
// parts share once). Every scene is loaded once (textures' headers only) so that a scene that
// does not load is refused here, naming the study file and the scene. The ids hash the scene's
// file name and the content of the files a job reads, not where they lie: a copy of the study
// and its scenes at another path plans the same ids.
std::vector<Job> planJobs(const StudySpec& spec);

// Writes DIR/jobs.jsonl (one job a line) and DIR/study.json (the study as read), each atomically.
void writePlan(const std::vector<Job>& jobs, const StudySpec& spec, const std::string& dir);

// DIR/jobs.jsonl, every row checked (a missing file or a row that is not a job: penumbra::Error
// naming the file and line, exit 2).
std::vector<Job> readPlan(const std::string& dir);

// The penumbra build a job's id includes (its source revision where the build knew it).
const char* buildIdentity();

}  // namespace penumbra::study
