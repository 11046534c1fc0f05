// FLIP, a perceptual difference of two images (Andersson, Nilsson, Akenine-Moeller, Oskarsson,
// Astroem and Fairchild, "FLIP: A Difference Evaluator for Alternating Images", HPG 2020), and
// its HDR variant (Andersson, Nilsson, Shirley and Akenine-Moeller, "Visualizing Errors in
// Rendered High Dynamic Range Images", Eurographics 2021 short papers). Written from the papers'
// descriptions; the constants are the papers'. Per pixel, in [0, 1]: 0 where a viewer who flips
// between the two images sees no difference, 1 at the largest colour difference (green against
// blue).
//
// LDR-FLIP (HPG 2020 section 4):
//  - colour pipeline: linear RGB -> XYZ -> YCxCz, the opponent space of Johnson and Fairchild
//    (CIELAB without the cube root); each channel convolved with the spatial form of its
//    contrast sensitivity function, a sum of Gaussians (achromatic, red-green, blue-yellow);
//    back to linear RGB clamped to [0, 1], then CIELAB with the Hunt adjustment (a*, b* scaled by
//    0.01 L*); the HyAB distance |dL| + sqrt(da^2 + db^2) to the power 0.7, remapped so that
//    the share pc = 0.4 of the largest distance (green-blue) maps to pt = 0.95;
//  - feature pipeline: edges (the first derivative of a Gaussian) and points (its second
//    derivative) of the luminance, sigma = 0.5 * 0.082 degrees; the larger of the edge and the
//    point magnitudes' differences, over sqrt(2), to the power 0.5;
//  - the error: colour ^ (1 - feature).
// HDR-FLIP (EG 2021): the LDR-FLIP of the two images at exposures 2^c, tone mapped (ACES, the
// fitted curve of Narkowicz 2016) and clamped, for evenly spaced c from c_start (the reference's
// largest luminance maps to 0.85) to c_stop (its median maps to 0.85), max(2, ceil(c_stop -
// c_start)) exposures; per pixel the largest.
//
// Where we diverge: images are convolved with clamp-to-edge borders (the papers do not say);
// the HDR exposure range ignores pixels of zero luminance for the median (a rendering's black
// background would otherwise make c_stop infinite), and a reference that is black everywhere is
// compared at exposure 0.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/image.h"

namespace penumbra {

// The papers' default observer: 0.7 m from a 0.7 m wide monitor of 3840 pixels,
// ppd = 0.7 * (3840 / 0.7) * pi / 180.
constexpr double kFlipDefaultPixelsPerDegree = 67.02;

// LDR-FLIP of two linear-RGB images (values clamped to [0, 1]) of the same size, 3 channels:
// a 1-channel map.
Image ldrFlip(const Image& test, const Image& reference, double pixelsPerDegree = kFlipDefaultPixelsPerDegree);

struct FlipExposures {
  double start = 0.0, stop = 0.0;  // c_start, c_stop (log2 of the exposure)
  int count = 1;
};
// HDR-FLIP's exposure range for `reference` (linear RGB, any range).
FlipExposures flipExposures(const Image& reference);

// The reference side of HDR-FLIP, perceived once at each exposure, for comparing many test
// images with one reference (compare: every technique against the converged reference).
class HdrFlipReference {
 public:
  HdrFlipReference(const Image& reference, double pixelsPerDegree = kFlipDefaultPixelsPerDegree);
  ~HdrFlipReference();
  HdrFlipReference(HdrFlipReference&&) noexcept;
  const FlipExposures& exposures() const;
  // The HDR-FLIP map of `test` (same size, linear RGB) against the reference.
  Image against(const Image& test) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// HDR-FLIP of two linear-RGB images (non-negative, any range): a 1-channel map.
Image hdrFlip(const Image& test, const Image& reference, double pixelsPerDegree = kFlipDefaultPixelsPerDegree,
              FlipExposures* used = nullptr);

// Mean of a 1-channel map over pixels where `valid` is 1 (all if empty).
double meanOf(const Image& map, const std::vector<std::uint8_t>& valid = {});

// A 1-channel map in [0, 1] as linear RGB in the magma colour map (the papers' heat maps).
Image flipHeatMap(const Image& map);

}  // namespace penumbra
