// `hard-sv`: hard shadows from the light centre with z-fail shadow volumes.
#pragma once

#include <cstddef>
#include <memory>

#include "pipeline/technique.h"

namespace penumbra {
// `bandBytes`: the most bytes one band of the count's buffers holds (shadow_volume.h
// storageBandBytes; 0: the GL's storage-block limit).
std::unique_ptr<Technique> makeHardShadowVolumes(std::size_t bandBytes = 0);
}  // namespace penumbra
