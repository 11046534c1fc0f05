// The explicit table of techniques: name -> factory. Add a technique here and nowhere else.
#include "core/error.h"
#include "techniques/registry.h"
#include "techniques/dcs/dcs.h"
#include "techniques/hard_sv/hard_sv.h"
#include "techniques/mvr/mvr.h"
#include "techniques/none/none.h"
#include "techniques/pcss/pcss.h"
#include "techniques/raytrace/raytrace.h"
#include "techniques/reproject/reproject.h"
#include "techniques/vssm/vssm.h"
#include "techniques/vwss/vwss.h"

namespace penumbra {

const std::vector<TechniqueInfo>& techniqueTable() {
  static const std::vector<TechniqueInfo> table = {
      {"none", "unshadowed direct lighting", [](const TechniqueParams&) { return makeUnshadowed(); }},
      {"hard-sv", "hard shadows from the light centre, z-fail shadow volumes (float counter)",
       [](const TechniqueParams&) { return makeHardShadowVolumes(); }},
      {"dcs", "depth complexity sampling: per-sample occluder counts, accurate silhouettes (exact; semi-opaque layers multiply)",
       [](const TechniqueParams&) { return makeDepthComplexitySampling({SilhouetteMode::Accurate}); }},
      {"dcs-standard", "depth complexity sampling with standard silhouettes (from the light centre)",
       [](const TechniqueParams&) { return makeDepthComplexitySampling({SilhouetteMode::Standard}); }},
      {"dcs-sum", "depth complexity sampling, semi-opaque occluders as the paper's sum of opacities",
       [](const TechniqueParams&) {
         DcsOptions o;
         o.opacity = dcs::OpacityMode::Sum;
         return makeDepthComplexitySampling(o);
       }},
      {"dcs-naive", "dcs with the paper's covered-sample loop over 8-bit packed positions (approximate)",
       [](const TechniqueParams&) {
         DcsOptions o;
         o.coverage = PENUMBRA_DCS_COVERAGE_NAIVE;
         return makeDepthComplexitySampling(o);
       }},
      {"dcs-lut", "dcs with the paper's edge LUT (cube-map sectors & line table, approximate)",
       [](const TechniqueParams&) {
         DcsOptions o;
         o.coverage = PENUMBRA_DCS_COVERAGE_LUT;
         return makeDepthComplexitySampling(o);
       }},
      {"mvr", "multi-view rasterisation: a depth map per light sample, one draw each, PCF (VWSS paper's reference)",
       [](const TechniqueParams& p) { return makeMultiViewRasterisation(p, false); }},
      {"mvr-layered", "mvr in one instanced draw, a geometry shader routing instances to map layers",
       [](const TechniqueParams& p) { return makeMultiViewRasterisation(p, true); }},
      {"vwss", "view-warped soft shadows: points from one enlarged central view, compute splat (buffered)",
       [](const TechniqueParams& p) { return makeViewWarpedSoftShadows(p, VwssMode::Buffered); }},
      {"vwss-unbuffered", "vwss splatting from the point-generation fragment shader (no point buffer)",
       [](const TechniqueParams& p) { return makeViewWarpedSoftShadows(p, VwssMode::Unbuffered); }},
      {"vwss-graphics", "vwss's points drawn as GL_POINTS, a draw per map, depth-tested (graphics pipeline)",
       [](const TechniqueParams& p) { return makeViewWarpedSoftShadows(p, VwssMode::Graphics); }},
      {"reproject", "fragment reprojection: the central z-buffered map reprojected into every map (atomics)",
       [](const TechniqueParams& p) { return makeFragmentReprojection(p, true); }},
      {"reproject-unsync", "fragment reprojection without synchronisation (last writer wins)",
       [](const TechniqueParams& p) { return makeFragmentReprojection(p, false); }},
      {"pcss", "percentage-closer soft shadows, one map from the light centre, Vogel disk + noise (Sterna: 32 blocker, 16 PCF samples)",
       [](const TechniqueParams& p) { return makePercentageCloserSoftShadows(p, pcssPreset(PcssMode::Regular, false, false)); }},
      {"pcss-ultra", "pcss with the 'Ultra' preset the VWSS paper compares with (64 blocker, 96 PCF samples)",
       [](const TechniqueParams& p) { return makePercentageCloserSoftShadows(p, pcssPreset(PcssMode::Regular, true, false)); }},
      {"pcss-mask", "pcss with Sterna's quarter-resolution blurred penumbra mask (kernel scale 1.4)",
       [](const TechniqueParams& p) { return makePercentageCloserSoftShadows(p, pcssPreset(PcssMode::PenumbraMask, false, false)); }},
      {"pcss-minfilter", "pcss with Sterna's min filter: blocker depth from the separable nearest-depth filter of the map, blurred",
       [](const TechniqueParams& p) { return makePercentageCloserSoftShadows(p, pcssPreset(PcssMode::MinFilter, false, false)); }},
      {"pcss-dense", "pcss as Fernando's original: every texel of the blocker-search and filter kernels (at most 32x32)",
       [](const TechniqueParams& p) { return makePercentageCloserSoftShadows(p, pcssPreset(PcssMode::Dense, false, false)); }},
      {"pcss-checker", "pcss computed on a checkerboard (half the pixels), depth-aware upsampling",
       [](const TechniqueParams& p) { return makePercentageCloserSoftShadows(p, pcssPreset(PcssMode::Regular, false, true)); }},
      {"vssm", "variance soft shadow mapping: exact summed-area table of depth moments, min-max HSM, 5x5 uniform blocker / H=3 adaptive shadow subdivision, contact fallback",
       [](const TechniqueParams& p) { return makeVarianceSoftShadowMapping(p, {}); }},
      {"vssm-uniform", "vssm with uniform subdivision for both kernels (5x5 blocker, 8x8 shadow)",
       [](const TechniqueParams& p) {
         VssmOptions o;
         o.shadowLevels = 0;
         return makeVarianceSoftShadowMapping(p, o);
       }},
      {"vssm-fp32", "vssm on a plain fp32 summed-area table (fails at large maps: hard case 17)",
       [](const TechniqueParams& p) {
         VssmOptions o;
         o.exactSat = false;
         return makeVarianceSoftShadowMapping(p, o);
       }},
      {"raytrace", "Embree reference with the same light samples as every technique (per sample)",
       [](const TechniqueParams&) { return makeRaytraceSameSamples(); }},
      {"raytrace-converged", "Embree reference, 1024 stratified samples per pixel (visibility only)",
       [](const TechniqueParams&) { return makeRaytraceConverged(1024); }},
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

std::vector<TechniqueInfo> findTechniques(const std::vector<std::string>& names) {
  std::vector<TechniqueInfo> out;
  for (auto& n : names) out.push_back(findTechnique(n));
  return out;
}

std::unique_ptr<Technique> makeTechnique(const std::string& name, const TechniqueParams& params) {
  return findTechnique(name).create(params);
}

}  // namespace penumbra
