// `vwss`: view-warped soft shadows (VWSS paper, section 3). The occluders are rasterised once
// from a central view moved back along the light normal until its frustum holds every light
// sample's (eq. 1-2), at a resolution raised by eq. 3, depth test off and back faces culled (unless needed, hard case
// 29): every fragment is a point. Buffered: the points go to a storage buffer and a compute shader splats each into
// several sample maps per thread with atomicMax (Listing 2); unbuffered: the point-generation fragment shader splats
// directly (Figure 3); graphics: the buffered points drawn as GL_POINTS, one draw per map, z-buffered by the depth test
// (Figure 13, bottom). Lighting: common/shadow_map/maps.h. Depth bias is applied there, after reprojection.
#pragma once

#include <memory>

#include "pipeline/technique.h"

namespace penumbra {

enum class VwssMode { Buffered, Unbuffered, Graphics };

// Parameters: those of common/shadow_map/maps.h, k (buffered), backfaces, scale, pass-points (buffered,
// graphics); vwss.cpp declares them.
std::vector<ParamSpec> vwssParams(VwssMode mode);
std::unique_ptr<Technique> makeViewWarpedSoftShadows(const TechniqueArgs& args, VwssMode mode);

}  // namespace penumbra
