// `reproject`: fragment reprojection (REPROJECT paper, section 3): one z-buffered
// depth map from the light centre, every texel rebuilt as a world point and reprojected into
// every light sample's map by a compute shader, synchronised with atomicMax (section 3.2) or not
// (`reproject-unsync`: plain stores, the last writer wins). Only the nearest surface of the
// central view survives, so disocclusions and the edges of the central frustum leak light
// (VWSS paper Figure 4, left): what VWSS's enlarged all-layers point set fixes.
#pragma once

#include <memory>

#include "pipeline/technique.h"

namespace penumbra {
// Parameters (besides the map ones): scale, k (reproject.cpp declares them).
std::vector<ParamSpec> reprojectParams();
std::unique_ptr<Technique> makeFragmentReprojection(const TechniqueArgs& args, bool synchronized);
}  // namespace penumbra
