// What compare measures of a technique's frames against a reference's (same scene, settings and
// samples): errors of the visibility buffer (all lights) and of the shaded image over surface
// pixels, with and without the 1-pixel band around the reference's shadow edges (core/metrics
// per image), per-sample agreement, and under --frames the flicker the reference does not have.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/metrics.h"
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
  std::int64_t sampleMismatches = 0;  // pairs that differ (outside the band)
  // The same agreement by the sample's distance from a rect light's centre
  // (LightResult::sampleRadius): rings [0, 1/4), [1/4, 1/2), [1/2, 3/4), [3/4, 1] of its
  // half-sides; -1 where a ring has no pairs or the light none (VWSS Fig. 8: views synthesised
  // from the centre's degrade away from it).
  static constexpr int kRings = 4;
  std::array<double, kRings> sampleAgreementByRing{-1.0, -1.0, -1.0, -1.0};
  // Pixels whose visibility decision differs (|dV| > 0.5 / N) outside the band.
  std::int64_t misclassifiedPixels = 0;
  // Pixels the technique left unshadowed by design (LightResult::unshadowed: shadow-map
  // receivers beyond max-angle), summed over lights, and the visibility error over the other
  // surface pixels (equal to `visibility` when there are none).
  std::int64_t unshadowedPixels = 0;
  ErrorStats visibilityExceptUnshadowed;
};

// A reference's own noise, from the variances it estimated for its pixels (FrameResult::
// colorVariance, LightResult::visibilityVariance): the root of their mean over surface pixels
// and channels (and lights), i.e. the RMSE its noise alone puts into any technique's error
// against it. Below it a technique's error is the reference's, not the technique's.
struct ReferenceNoise {
  double visibility = 0.0;  // all lights' visibility buffers
  double shaded = 0.0;      // the shaded image
};
// Null when the frame's technique estimated no noise.
std::optional<ReferenceNoise> referenceNoise(const FrameResult& reference);

// Errors of `frame` against `reference` (same scene, settings and samples).
TechniqueErrors measureErrors(const FrameResult& frame, const FrameResult& reference);

// One frame's visibility, every light's buffer stacked vertically, and its surface mask per
// pixel of the stack: what the temporal measures keep of a frame (not the whole FrameResult).
struct FrameVisibility {
  Image visibility;
  std::vector<std::uint8_t> valid;
};
FrameVisibility keepVisibility(const FrameResult& frame);

// Of a technique's frames against the reference's frames (same times, at least two).
struct TemporalErrors {
  // RMS over frames f >= 1, surface pixels of both frames, lights and channels of the change
  // from frame f-1 in the technique's visibility minus the reference's: flicker the reference
  // does not have.
  double flicker = 0.0;
  double referenceMotion = 0.0;  // the same RMS of the reference's own change
  double meanFrameRmse = 0.0;    // the mean over frames of the visibility RMSE (reference's surface)
};
TemporalErrors measureTemporal(const std::vector<FrameVisibility>& frames,
                               const std::vector<FrameVisibility>& reference);

}  // namespace penumbra
