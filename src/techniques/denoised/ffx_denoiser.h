// A shadow denoiser after AMD FidelityFX's shadow denoiser ([FFX-Denoiser]: its published
// description, not its code), the second denoiser of raytrace-denoised (`denoiser=ffx`, row
// `raytrace-ffx`), on the same rays and samples as ours so that the two are compared on equal
// input. Per frame, on the traced shadow ratio (one ray a pixel: 0 or 1):
//  1. tile classification: a bit a pixel (ratio >= 1/2) in a 32-bit mask a tile of 8 x 4; a tile
//     whose own and whose 8 neighbours' traced ratios are all exactly lit or all exactly
//     shadowed has no spatial variance and is not filtered (its pixels keep that value, and the
//     history restarts from it);
//  2. temporal: the pixel's history (mean and second moment of the ratio, and their length) is
//     reprojected through the previous camera and dropped where the depth there differs by more
//     than 1% (disocclusion by depth, and by normal), clamped to the local neighbourhood's mean
//     +- `clamp` standard deviations (a 7 x 7 kernel of the current ratio's moments: no
//     ghosting), and accumulated (a running mean up to `history` frames, as ours);
//  3. variance: the history's (second moment minus the squared mean) over its length, or the
//     neighbourhood's where the history is shorter than 4 frames: the spatial filter is strong
//     where there are few temporal samples and cools off as they grow;
//  4. three a-trous passes (steps 1, 2, 4; a 3 x 3 kernel of weights 1/4, 1/2, 1/4) whose edge
//     stops are the plane distance and the normals (ours) and the ratio's difference over 4
//     standard deviations (the variance filtered along, as in SVGF).
// Divergences: on the CPU over the pipeline's G-buffer (the reprojection is the camera's, the
// scenes' animation is rigid); the ratio may be any value with spp > 1 (the tile bit is its
// rounding).
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"
#include "scene/gbuffer.h"
#include "techniques/denoised/filtering.h"

namespace penumbra::denoise {

struct FfxOptions {
  bool temporal = true;
  int maxHistory = 16;
  double clampSigma = 1.0;  // neighbourhood clamp, standard deviations
};

// One light's history.
struct FfxHistory {
  Image mean, second;  // RGB: the accumulated ratio and its second moment
  std::vector<int> length;
  std::vector<float> depth;  // distance to the eye
  std::vector<glm::vec3> normal;
  std::vector<std::uint8_t> valid;
  Camera camera;
  glm::dvec3 origin{0.0};
};

struct FfxStatistics {
  double uniformTiles = 0.0;  // the share of tiles with a surface that needed no filtering
  double meanHistory = 0.0;
};

// The denoised ratio of `ratio` (the traced samples' shadow ratio a pixel); updates `history`.
Image ffxDenoise(const CpuGBuffer& g, const Camera& camera, const Image& ratio, FfxHistory& history,
                 const FfxOptions& options, FfxStatistics& statistics);

}  // namespace penumbra::denoise
