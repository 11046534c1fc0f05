// The explicit table of techniques: name -> factory. Add a technique here and nowhere else.
#include "core/error.h"
#include "pipeline/technique.h"
#include "techniques/dcs/dcs.h"
#include "techniques/hard_sv/hard_sv.h"
#include "techniques/none/none.h"
#include "techniques/raytrace/raytrace.h"

namespace penumbra {

const std::vector<TechniqueInfo>& techniqueTable() {
  static const std::vector<TechniqueInfo> table = {
      {"none", "unshadowed direct lighting", [] { return makeUnshadowed(); }},
      {"hard-sv", "hard shadows from the light centre, z-fail shadow volumes (float counter)",
       [] { return makeHardShadowVolumes(); }},
      {"dcs", "depth complexity sampling: per-sample occluder counts, accurate silhouettes (exact; semi-opaque layers multiply)",
       [] { return makeDepthComplexitySampling({SilhouetteMode::Accurate}); }},
      {"dcs-standard", "depth complexity sampling with standard silhouettes (from the light centre)",
       [] { return makeDepthComplexitySampling({SilhouetteMode::Standard}); }},
      {"dcs-sum", "depth complexity sampling, semi-opaque occluders as the paper's sum of opacities",
       [] {
         DcsOptions o;
         o.opacity = dcs::OpacityMode::Sum;
         return makeDepthComplexitySampling(o);
       }},
      {"dcs-naive", "dcs with the paper's covered-sample loop over 8-bit packed positions (approximate)",
       [] {
         DcsOptions o;
         o.coverage = PENUMBRA_DCS_COVERAGE_NAIVE;
         return makeDepthComplexitySampling(o);
       }},
      {"dcs-lut", "dcs with the paper's edge LUT (cube-map sectors & line table, approximate)",
       [] {
         DcsOptions o;
         o.coverage = PENUMBRA_DCS_COVERAGE_LUT;
         return makeDepthComplexitySampling(o);
       }},
      {"raytrace", "Embree reference with the same light samples as every technique (per sample)",
       [] { return makeRaytraceSameSamples(); }},
      {"raytrace-converged", "Embree reference, 1024 stratified samples per pixel (visibility only)",
       [] { return makeRaytraceConverged(1024); }},
  };
  return table;
}

const TechniqueInfo& findTechnique(const std::string& name) {
  std::string known;
  for (auto& t : techniqueTable()) {
    if (t.name == name) return t;
    known += (known.empty() ? "" : ", ") + t.name;
  }
  throw Error("--technique", "unknown technique '" + name + "' (known: " + known + ")", ExitCode::Usage);
}

}  // namespace penumbra
