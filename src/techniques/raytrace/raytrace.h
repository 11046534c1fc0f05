// `raytrace` and `raytrace-converged`: the Embree reference behind the technique interface.
#pragma once

#include <memory>
#include <vector>

#include "pipeline/technique.h"

namespace penumbra {
// Same samples: exactly the light samples every GPU technique uses; per-sample results.
std::unique_ptr<Technique> makeRaytraceSameSamples();
// Converged: per pixel, batches of fresh stratified light samples for the visibility buffer, the
// shaded image by MIS of the light and the BRDF to a target standard error
// (shading/light_integral.h), and each one's noise (CpuShading); no per-sample results. Its
// parameters (`reference-*`) are read by compare's converged reference too.
std::vector<ParamSpec> raytraceConvergedParams();
std::unique_ptr<Technique> makeRaytraceConverged(const TechniqueArgs& args);
}  // namespace penumbra
