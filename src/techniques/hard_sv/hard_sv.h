// `hard-sv`: hard shadows from the light centre with z-fail shadow volumes.
#pragma once

#include <memory>

#include "pipeline/technique.h"

namespace penumbra {
std::unique_ptr<Technique> makeHardShadowVolumes();
}  // namespace penumbra
