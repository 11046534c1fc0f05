// Error metrics between a technique's image and the reference image (same size, same channel
// count). Used identically for the visibility buffer and the shaded image.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"

namespace penumbra {

struct ErrorStats {
  double rmse = 0.0;            // sqrt(mean over counted pixels and channels of (a-b)^2)
  double meanAbs = 0.0;         // mean over counted pixels and channels of |a-b|
  double maxAbs = 0.0;          // max over counted pixels and channels of |a-b|
  std::int64_t pixelsOver = 0;  // counted pixels where any channel differs by more than 1/255
  std::int64_t pixelsCounted = 0;
};

// Mask of pixels to exclude: 1 where the pixel lies within `radius` pixels (Chebyshev distance)
// of a shadow edge of `reference`, i.e. of a pixel whose neighbour differs in visibility by more
// than `threshold` in any channel. Pixels with mask 1 are left out of the statistics.
// Both pixels of a differing 4-neighbour pair are edge pixels, so radius 0 marks exactly those
// (a two-pixel-wide line along a hard edge) and each radius step widens it by one on each side.
std::vector<std::uint8_t> edgeBandMask(const Image& reference, int radius = 1, float threshold = 1e-4f);

// Statistics of a against b over pixels where `exclude` is 0 (or all pixels if exclude is
// empty) and where `valid` is 1 (or all if empty; e.g. background pixels can be left out).
// A NaN difference makes rmse, meanAbs and maxAbs NaN and counts its pixel in pixelsOver.
ErrorStats compareImages(const Image& a, const Image& b, const std::vector<std::uint8_t>& exclude = {},
                         const std::vector<std::uint8_t>& valid = {});

// False-colour heat map (RGB, linear) of the per-pixel max-channel absolute error, mapped
// 0 -> black/blue, `scale` -> red/white (a perceptually ordered ramp). Excluded pixels grey.
Image errorHeatMap(const Image& a, const Image& b, float scale, const std::vector<std::uint8_t>& exclude = {});

}  // namespace penumbra
