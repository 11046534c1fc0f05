// `mvr`: multi-view rasterisation (Heckbert & Herf 1997; the VWSS paper's MVR reference): the
// occluders rasterised into one 32-bit depth map per light sample, then per-sample shadow
// mapping with PCF (techniques/common/shadow_map/maps.h).
#pragma once

#include <memory>

#include "pipeline/technique.h"

namespace penumbra {
// layered: one instanced draw, a geometry shader routing each instance to its map layer;
// otherwise one draw per map.
std::vector<ParamSpec> mvrParams();
std::unique_ptr<Technique> makeMultiViewRasterisation(const TechniqueArgs& args, bool layered);
}  // namespace penumbra
