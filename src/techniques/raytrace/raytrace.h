// `raytrace` and `raytrace-converged`: the Embree reference behind the technique interface.
#pragma once

#include <memory>

#include "pipeline/technique.h"

namespace penumbra {
// Same samples: exactly the light samples every GPU technique uses; per-sample results.
std::unique_ptr<Technique> makeRaytraceSameSamples();
// Converged: `samples` stratified samples per pixel (a fresh set per pixel); visibility and the
// shaded image (per-sample direct illumination with the same BRDF), no per-sample results.
std::unique_ptr<Technique> makeRaytraceConverged(int samples = 1024);
}  // namespace penumbra
