// A study as data (docs/studies.md): the scenes, techniques with their parameter sweeps, light
// sample counts, image sizes, seeds and sample strategies of one question, and its references.
// readStudy checks it as the scene loader checks a scene: every error is one line naming the
// file, the key and the problem (exit 2), and nothing a user wrote is silently ignored (an
// unknown key is an error).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra::study {

// One technique row of the study and the parameter sets its sweeps expand to (the product of
// the sweeps, each set "key=value" strings; one empty set without sweeps).
struct TechniqueAxis {
  std::string name;
  std::vector<std::vector<std::string>> paramSets;
};

struct Size {
  int width = 0, height = 0;  // height 0: the scene's aspect
};

struct StudySpec {
  std::string name;
  std::string path;                 // the study file, for messages
  std::vector<std::string> scenes;  // files (globs expanded, sorted) or "default"
  std::vector<TechniqueAxis> techniques;
  std::vector<int> samples;
  std::vector<Size> sizes;
  std::vector<std::uint32_t> seeds;
  std::vector<std::string> strategies;  // sampling/light_samples.h kSampleStrategyNames
  bool converged = false;               // also measure against raytrace-converged
  int convergedSamples = 1024;          // its light samples a pixel
  int frames = 3, warmup = 1;           // timed frames and warm-up frames per job
  std::string images = "all";           // what a job keeps: "all" (EXR and PNG), "png", "none"
};

// Reads and checks a study file (JSON). Scene paths and globs are relative to the study file's
// folder unless absolute; techniques and their parameters are checked against the table of
// techniques (a parameter out of range is refused here, not in a job).
StudySpec readStudy(const std::string& path);

// The study's job count (techniques x parameter sets x scenes x samples x sizes x seeds x
// strategies, plus the references), computed without expanding anything.
std::uint64_t jobCount(const StudySpec& spec);

}  // namespace penumbra::study
