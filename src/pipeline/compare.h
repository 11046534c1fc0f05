// Comparing techniques with the Embree reference on the same light samples: the same code for
// the CLI's `compare` and the tests. Errors are measured on the visibility buffer (per light) and
// on the shaded image, over pixels with a surface, with and without the 1-pixel band around
// the reference's shadow edges.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/metrics.h"
#include "gl/context.h"
#include "pipeline/renderer.h"

namespace penumbra {

struct TechniqueErrors {
  ErrorStats visibility;             // all lights' visibility buffers, surface pixels
  ErrorStats visibilityOutsideBand;  // ... outside the 1-pixel edge band
  ErrorStats shaded;
  ErrorStats shadedOutsideBand;
  // Per-(pixel, sample) agreement outside the band (both results per-sample), else -1.
  double sampleAgreement = -1.0;
  std::int64_t samplePairs = 0;
  // Pixels whose visibility decision differs (|dV| > 0.5 / N) outside the band.
  std::int64_t misclassifiedPixels = 0;
};

// Errors of `frame` against `reference` (same scene, settings and samples).
TechniqueErrors measureErrors(const FrameResult& frame, const FrameResult& reference);

// Writes .exr (layers: RGB colour, "visibility" for light 0, "visibility1".. for the others)
// or .png (colour, sRGB). Other extensions: penumbra::Error.
void writeFrame(const std::string& path, const FrameResult& frame, float exposure = 0.0f);

nlohmann::json frameSummary(const FrameResult& frame);
nlohmann::json errorsJson(const TechniqueErrors& e);

struct CompareReport {
  nlohmann::json json;  // report.json
  std::string table;    // human-readable table
  std::vector<std::pair<std::string, double>> visibilityRmse;  // per technique
};

// Renders the reference (`raytrace`, same samples) and each technique, writes
// <outDir>/<technique>.exr/.png, <technique>_heat.png (visibility error, 0..0.25) and returns
// the report. `outDir` empty: write nothing.
// `params` (--param) go to every technique; a key none of them reads is refused.
CompareReport compareTechniques(gl::Context& context, const Scene& scene, const RenderSettings& settings,
                                const std::vector<std::string>& techniques, const std::string& outDir,
                                const TechniqueParams& params = {});

}  // namespace penumbra
