// Comparing techniques with the Embree reference on the same light samples: the same code for
// the CLI's `compare` and the tests. A comparison run covers presets (compare/presets.h: the
// cartesian product of the sweep axes), each with its own same-sample reference (and, with
// `converged`, the converged reference of its resolution); every technique is timed (warm-up,
// then the median and spread of each stage) and measured (compare/measure.h) at each preset that
// changes what it renders, its images written as it goes (compare/output.h).
// compare/report.h writes the result as JSON, CSV, a table, an SVG plot and an HTML page.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "compare/insets.h"
#include "compare/measure.h"
#include "compare/output.h"
#include "compare/presets.h"
#include "core/flip.h"
#include "gl/context.h"
#include "pipeline/renderer.h"
#include "pipeline/timing.h"

namespace penumbra {

struct CompareResult;

struct CompareOptions {
  // What is compared, and the references it is compared with (techniques/registry.h hands them
  // in: findTechnique("raytrace"), findTechnique("raytrace-converged")): compare looks nothing
  // up by name.
  std::vector<TechniqueInfo> techniques;
  TechniqueInfo reference;           // same samples, per sample
  TechniqueInfo convergedReference;  // with `converged` (or a samples sweep)
  std::vector<std::string> params;   // --param key=value, for every technique
  std::vector<SweepAxis> sweeps;
  bool converged = false;            // also measure against raytrace-converged (forced by a samples sweep)
  int timingFrames = 3, warmup = 1;  // per technique and preset
  std::vector<Inset> insets;         // empty: chooseInsets on the first preset's reference
  // Temporal stability: frames rendered at time + f / fps (scene animation, "spin" in the
  // scene file, and animated light textures); 1 = a still.
  int frames = 1;
  float fps = 30.0f;
  std::string outDir;       // images are written here as they are made; empty: nothing written
  bool writeImages = true;  // PNG images, heat maps and insets
  bool writeExr = true;     // float images with the visibility layers
  int progress = -1;        // Progress's `interactive`: -1 from isatty
  // Called after every row (reference, technique, failure) with the result so far, its info's
  // "incomplete" saying how many rows of how many: the report rewritten as the run goes, so an
  // interrupted run leaves a report that says it is incomplete.
  std::function<void(const CompareResult&)> onRow;
  // FLIP's observer (core/flip.h): pixels per degree of visual angle, the papers' default.
  double pixelsPerDegree = kFlipDefaultPixelsPerDegree;
  // References rendered by another run (a study's reference jobs, study/run.h), used instead of
  // rendering them: the same-sample one (its row is then not part of the result: it is that other
  // run's) and the converged one. Only for one preset, one frame.
  const FrameResult* givenReference = nullptr;
  const FrameResult* givenConverged = nullptr;
  // Called with the same-sample reference's frame 0 once it is rendered (a study keeps it for its
  // technique jobs).
  std::function<void(const FrameResult&)> onReference;
};

// What a speed-against-error plot puts on its error axis.
enum class ErrorAxis { Visibility, Shaded, Flip };
const char* toString(ErrorAxis a);

// One technique (or a reference) at one preset.
struct CompareRun {
  std::string technique;
  TechniqueFamily family = TechniqueFamily::ExactPerSample;
  std::size_t preset = 0;           // index into CompareResult::presets
  bool reference = false;           // raytrace (same samples) or raytrace-converged
  std::vector<std::string> params;  // key=value of the given parameters this technique read
  std::string shading;
  std::vector<std::pair<std::string, Spread>> stages;  // ms; "prepare" left out
  Spread total;                                        // ms per frame, stages summed: the technique's time
  // The harness's readbacks and uploads (StageKind::Harness), apart from `total`.
  std::vector<std::pair<std::string, Spread>> harnessStages;
  Spread harness;
  // The GL's pipeline statistics of the last timed frame per stage of `stages` (empty where the
  // GL counts none: CompareResult::info["pipelineStatistics"] says why).
  std::vector<std::pair<std::string, PipelineCounts>> counts;
  double prepareMs = 0.0;  // once per scene
  std::size_t memoryBytes = 0;
  std::vector<std::pair<std::string, double>> statistics;
  std::vector<std::string> notes;            // FrameResult::notes of the first frame
  TechniqueErrors errors;                    // against the same-sample reference
  std::optional<TechniqueErrors> converged;  // against raytrace-converged
  // The same-sample reference's row of a comparison with a converged reference: that converged
  // reference's own noise (compare/measure.h) and its statistics (samples per pixel, ...).
  std::optional<ReferenceNoise> referenceNoise;
  std::vector<std::pair<std::string, double>> referenceStatistics;
  // --frames > 1: RMS over frames and surface pixels of (this frame's change in visibility
  // - the reference's change), i.e. flicker the reference does not have; the reference's own
  // RMS change; the mean visibility RMSE over the frames.
  double flicker = -1.0, referenceMotion = -1.0, meanFrameRmse = -1.0;
  // Mean HDR-FLIP (core/flip.h) of the shaded image over surface pixels against the converged
  // reference (or, without one, the same-sample reference; the same-sample reference itself
  // then has none); NaN where an image had a non-finite pixel.
  std::optional<double> flip;
  // The technique failed (an Error or another exception while it was created or rendered):
  // `failure` says why; no timings, errors or images. The other runs go on; a failed reference
  // ends the comparison (compareTechniques throws).
  bool failed = false;
  std::string failure;
  std::string image, heat;     // file names in the output folder, "" if not written
  std::string flipHeat;        // the FLIP map in magma, "" if not written
  std::string unshadowedMask;  // white where frame 0 left a pixel unshadowed in any light, "" if none
  std::vector<std::string> insetImages;
  // The error the plot uses: visibility RMSE against the converged reference if measured,
  // else against the same-sample one.
  double plotError() const { return converged ? converged->visibility.rmse : errors.visibility.rmse; }
  // The error the plot's other axes use (ErrorAxis): the shaded image's RMSE against the same
  // reference as plotError, or the mean FLIP.
  double errorOn(ErrorAxis axis) const;
};

// The converged references' noise on `axis` (the plot's error floors), one per image size, in
// the order of the runs; none on the FLIP axis.

// The sum of a run's pipeline statistics over its stages.
PipelineCounts totalCounts(const CompareRun& run);

struct CompareResult {
  nlohmann::json info;  // scene, renderer, GL version, settings, parameters, sweeps
  std::vector<ComparePreset> presets;
  std::vector<CompareRun> runs;  // in rendering order, references first in each preset
  std::vector<Inset> insets;
  std::string insetSource;  // "given" or "chosen"
  bool hasConverged() const;
  bool hasTemporal() const;
  bool hasFlip() const;
  nlohmann::json json() const;  // report.json
};

// The converged references' noise on `axis` (the plot's error floors), one per image size, in
// the order of the runs; none on the FLIP axis.
std::vector<std::pair<const ComparePreset*, double>> referenceNoiseOn(const CompareResult& r, ErrorAxis axis);

// What compareTechniques refuses before it renders (sweeps, insets, every technique created with
// its parameters at every preset), without a GL context: a bad parameter costs no GL setup.
void checkComparison(const RenderSettings& settings, const CompareOptions& options);

// Renders the references and every technique at every preset, writing images (.exr, .png,
// heat maps, inset crops) into options.outDir as it goes. Parameters are checked (a key no
// technique reads is refused) before the first render. A technique that fails is a run with
// `failed` set (the others go on); a reference that fails throws.
CompareResult compareTechniques(gl::Context& context, const Scene& scene, const RenderSettings& settings,
                                const CompareOptions& options);

}  // namespace penumbra
