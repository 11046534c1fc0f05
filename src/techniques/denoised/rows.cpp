// The denoised folder's row in the table of techniques (registry.h).
#include "techniques/denoised/denoised.h"
#include "techniques/registry.h"

namespace penumbra {

std::vector<TechniqueInfo> denoisedRows() {
  return {{"raytrace-denoised",
           "1-4 shadow rays per pixel through Embree, temporal accumulation and a penumbra-sized cross-bilateral "
           "filter (NRD SIGMA style)",
           denoisedParams("ours"), makeRaytraceDenoised, TechniqueFamily::Denoised},
          {"raytrace-ffx",
           "the same rays denoised after AMD FidelityFX's shadow denoiser: 8x4 tile classification, depth "
           "disocclusion, neighbourhood-clamped moments, three a-trous passes",
           denoisedParams("ffx"), makeRaytraceDenoised, TechniqueFamily::Denoised}};
}

}  // namespace penumbra
