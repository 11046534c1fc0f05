// The raytrace folder's rows in the table of techniques (registry.h): the Embree reference
// (src/reference) as techniques.
#include "techniques/raytrace/raytrace.h"
#include "techniques/registry.h"

namespace penumbra {

std::vector<TechniqueInfo> raytraceRows() {
  return {
      {"raytrace",
       "Embree reference with the same light samples as every technique (per sample)",
       {},
       [](const TechniqueArgs&) { return makeRaytraceSameSamples(); },
       TechniqueFamily::ExactPerSample},
      {"raytrace-converged",
       "Embree reference: visibility from 2048+ stratified light samples per pixel, the shaded image by MIS of light "
       "and BRDF to a 1e-3 relative standard error (65536 samples at most), each with its noise",
       raytraceConvergedParams(), makeRaytraceConverged, TechniqueFamily::ExactPerSample},
  };
}

}  // namespace penumbra
