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
  // Parameters of one more, untimed frame whose statistics the job reports instead of the timed
  // frames' (dcs `profile=true`: counters that would slow the timed frames).
  std::vector<std::string> profile;
};

// A scene of the study: a file (or "default") and what is changed in memory before it renders
// (scene/variants.h: "opacity=1" an opaque twin of a semi-opaque scene, "copies=5",
// "spacing=1.6" the occluders instanced on a grid), "key=value" strings in key order.
struct SceneEntry {
  std::string path;
  std::vector<std::string> variant;
  bool operator==(const SceneEntry& o) const { return path == o.path && variant == o.variant; }
};

struct Size {
  int width = 0, height = 0;  // height 0: the scene's aspect
};

// The axes of a study (or of one of its parts): every combination is a configuration.
struct StudyAxes {
  std::vector<SceneEntry> scenes;  // files (globs expanded, sorted) or "default", with variants
  std::vector<TechniqueAxis> techniques;
  std::vector<int> samples = {16};
  std::vector<Size> sizes = {{128, 0}};
  std::vector<std::uint32_t> seeds = {1};
  std::vector<std::string> strategies = {"stratified"};  // sampling/light_samples.h kSampleStrategyNames
  std::vector<double> lightScales = {1.0};               // every light's extent times this
  std::vector<std::string> shadings = {"ratio"};         // pipeline/renderer.h kShadingModeNames
  std::vector<std::string> patterns = {"correlated"};    // sampling/light_samples.h kPixelPatternNames
  int frames = 3, warmup = 1;                            // timed frames and warm-up frames per job
  bool converged = false;                                // also measure against raytrace-converged
  int convergedSamples = 1024;                           // its light samples a pixel
};

struct StudySpec : StudyAxes {
  std::string name;
  std::string path;            // the study file, for messages
  std::string images = "all";  // what a job keeps: "all" (EXR and PNG), "png", "none"
  // `parts`: several products in one study (each part's axes default to the study's); the plan
  // is their union, a job two parts share planned once. Empty: the study's own axes.
  std::vector<StudyAxes> parts;
  // The products to plan: the parts, or the study's own axes.
  std::vector<StudyAxes> products() const;
  // Every scene of every product, once, in order.
  std::vector<SceneEntry> allScenes() const;
};

// Reads and checks a study file (JSON). Scene paths and globs are relative to the study file's
// folder unless absolute; techniques and their parameters are checked against the table of
// techniques (a parameter out of range is refused here, not in a job).
StudySpec readStudy(const std::string& path);

// The study's job count (per product: techniques x parameter sets x scenes x samples x sizes x
// seeds x strategies x light scales x shadings x patterns, plus the references), computed
// without expanding anything; an upper bound where parts share jobs.
std::uint64_t jobCount(const StudySpec& spec);

}  // namespace penumbra::study
