// `raytrace-denoised`: the point the industry plots today, a few shadow rays per pixel and a
// shadow denoiser, in the manner of NVIDIA NRD's SIGMA and AMD FidelityFX's shadow denoiser:
//  1. `spp` rays per pixel through Embree (the pixel's own light samples above its horizon, a
//     different `spp` of those M each frame: every one once in M / spp frames; embree_reference.h
//     sparseSamples), giving
//     the shadow ratio sum L T / sum L of those samples and their occluders' distance;
//  2. temporal accumulation (`temporal`): the ratio's running mean over up to `history` frames
//     (0: N / spp, one cycle of the samples), reprojected through the previous frame's camera,
//     reset where the surface there was another (disocclusion: position or normal), and its
//     history clamped to the current frame's filtered value +- 0.25 (moving shadows);
//  3. a spatial cross-bilateral filter on the G-buffer (normal and plane-distance edge stops)
//     whose radius follows the penumbra estimated from the occluders' distance by parallel planes
//     (the light's half size x d_blocker / (d_light - d_blocker), over the pixel's footprint),
//     shrunk by the square root of the history length, at most `max-radius` pixels.
// The visibility is the denoised ratio times the pixel's unshadowed V (its N samples above the
// horizon), so the pipeline's ratio shading gets the ratio back. CPU (Embree and the filter);
// no per-sample results.
#pragma once

#include <memory>

#include "pipeline/technique.h"

namespace penumbra {

// `denoiser`: the default of the denoiser parameter ("ours" or "ffx": ffx_denoiser.h).
std::vector<ParamSpec> denoisedParams(const std::string& denoiser);
std::unique_ptr<Technique> makeRaytraceDenoised(const TechniqueArgs& args);

}  // namespace penumbra
