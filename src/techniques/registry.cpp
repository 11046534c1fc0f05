// The explicit table of techniques: name -> factory. Add a technique here and nowhere else.
#include "core/error.h"
#include "techniques/registry.h"
#include "techniques/dcs/dcs.h"
#include "techniques/denoised/denoised.h"
#include "techniques/evsm/evsm.h"
#include "techniques/hard_sv/hard_sv.h"
#include "techniques/msm/msm.h"
#include "techniques/mvr/mvr.h"
#include "techniques/none/none.h"
#include "techniques/pcss/pcss.h"
#include "techniques/raytrace/raytrace.h"
#include "techniques/reproject/reproject.h"
#include "techniques/vssm/vssm.h"
#include "techniques/vwss/vwss.h"

namespace penumbra {

namespace {
DcsOptions dcsPreset(SilhouetteMode silhouettes, dcs::OpacityMode opacity, int coverage) {
  DcsOptions o;
  o.silhouettes = silhouettes;
  o.opacity = opacity;
  o.coverage = coverage;
  return o;
}
TechniqueInfo dcsEntry(std::string name, std::string description, DcsOptions preset) {
  return {std::move(name), std::move(description), dcsParams(preset),
          [](const TechniqueArgs& a) { return makeDepthComplexitySampling(readDcsOptions(a)); },
          TechniqueFamily::ExactPerSample};
}
// A technique that is a preset of a family: the family's declarations with the preset's
// defaults, and its factory.
template <class Preset>
TechniqueInfo presetEntry(std::string name, std::string description, std::vector<ParamSpec> params, Preset preset,
                          std::unique_ptr<Technique> (*make)(const TechniqueArgs&, Preset), TechniqueFamily family) {
  return {std::move(name), std::move(description), std::move(params),
          [preset, make](const TechniqueArgs& a) { return make(a, preset); }, family};
}
TechniqueInfo pcssEntry(std::string name, std::string description, PcssOptions preset) {
  return presetEntry(std::move(name), std::move(description), pcssParams(preset), preset, makePercentageCloserSoftShadows,
                     TechniqueFamily::SingleMap);
}
TechniqueInfo vssmEntry(std::string name, std::string description, VssmOptions preset) {
  return presetEntry(std::move(name), std::move(description), vssmParams(preset), preset, makeVarianceSoftShadowMapping,
                     TechniqueFamily::SingleMap);
}
TechniqueInfo vwssEntry(std::string name, std::string description, VwssMode mode) {
  return presetEntry(std::move(name), std::move(description), vwssParams(mode), mode, makeViewWarpedSoftShadows,
                     TechniqueFamily::MultiView);
}
TechniqueInfo msmEntry(std::string name, std::string description, MsmOptions preset) {
  return presetEntry(std::move(name), std::move(description), msmParams(preset), preset, makeMomentShadowMapping,
                     TechniqueFamily::SingleMap);
}
MsmOptions msmPreset(bool soft) {
  MsmOptions o;
  o.soft = soft;
  return o;
}
VssmOptions vssmPreset(bool exactSat, int shadowLevels) {
  VssmOptions o;
  o.exactSat = exactSat;
  o.shadowLevels = shadowLevels;
  return o;
}
}  // namespace

const std::vector<TechniqueInfo>& techniqueTable() {
  using dcs::OpacityMode;
  static const std::vector<TechniqueInfo> table = {
      {"none", "unshadowed direct lighting", {}, [](const TechniqueArgs&) { return makeUnshadowed(); }, TechniqueFamily::Hard},
      {"hard-sv", "hard shadows from the light centre, z-fail shadow volumes (float counter)", {},
       [](const TechniqueArgs&) { return makeHardShadowVolumes(); }, TechniqueFamily::Hard},
      dcsEntry("dcs", "depth complexity sampling: per-sample occluder counts, accurate silhouettes (exact; semi-opaque layers multiply)",
               dcsPreset(SilhouetteMode::Accurate, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_EXACT)),
      dcsEntry("dcs-standard", "depth complexity sampling with standard silhouettes (from the light centre)",
               dcsPreset(SilhouetteMode::Standard, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_EXACT)),
      dcsEntry("dcs-sum", "depth complexity sampling, semi-opaque occluders as the paper's sum of opacities",
               dcsPreset(SilhouetteMode::Accurate, OpacityMode::Sum, PENUMBRA_DCS_COVERAGE_EXACT)),
      dcsEntry("dcs-naive", "dcs with the paper's covered-sample loop over 8-bit packed positions (approximate)",
               dcsPreset(SilhouetteMode::Accurate, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_NAIVE)),
      dcsEntry("dcs-lut", "dcs with the paper's edge LUT (cube-map sectors & line table, approximate)",
               dcsPreset(SilhouetteMode::Accurate, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_LUT)),
      {"mvr", "multi-view rasterisation: a depth map per light sample, one draw each, PCF (VWSS paper's reference)",
       mvrParams(), [](const TechniqueArgs& a) { return makeMultiViewRasterisation(a, false); }, TechniqueFamily::MultiView},
      {"mvr-layered", "mvr in one instanced draw, a geometry shader routing instances to map layers", mvrParams(),
       [](const TechniqueArgs& a) { return makeMultiViewRasterisation(a, true); }, TechniqueFamily::MultiView},
      vwssEntry("vwss", "view-warped soft shadows: points from one enlarged central view, compute splat (buffered)",
                VwssMode::Buffered),
      vwssEntry("vwss-unbuffered", "vwss splatting from the point-generation fragment shader (no point buffer)",
                VwssMode::Unbuffered),
      vwssEntry("vwss-graphics", "vwss's points drawn as GL_POINTS, a draw per map, depth-tested (graphics pipeline)",
                VwssMode::Graphics),
      {"reproject", "fragment reprojection: the central z-buffered map reprojected into every map (atomics)",
       reprojectParams(), [](const TechniqueArgs& a) { return makeFragmentReprojection(a, true); }, TechniqueFamily::MultiView},
      {"reproject-unsync", "fragment reprojection without synchronisation (last writer wins)", reprojectParams(),
       [](const TechniqueArgs& a) { return makeFragmentReprojection(a, false); }, TechniqueFamily::MultiView},
      pcssEntry("pcss", "percentage-closer soft shadows, one map from the light centre, Vogel disk + noise (Sterna: 32 blocker, 16 PCF samples)",
                pcssPreset(PcssMode::Regular, false, false)),
      pcssEntry("pcss-ultra", "pcss with the 'Ultra' preset the VWSS paper compares with (64 blocker, 96 PCF samples)",
                pcssPreset(PcssMode::Regular, true, false)),
      pcssEntry("pcss-mask", "pcss with Sterna's quarter-resolution blurred penumbra mask (kernel scale 1.4)",
                pcssPreset(PcssMode::PenumbraMask, false, false)),
      pcssEntry("pcss-minfilter", "pcss with Sterna's min filter: blocker depth from the separable nearest-depth filter of the map, blurred",
                pcssPreset(PcssMode::MinFilter, false, false)),
      pcssEntry("pcss-dense", "pcss as Fernando's original: every texel of the blocker-search and filter kernels (at most 32x32)",
                pcssPreset(PcssMode::Dense, false, false)),
      pcssEntry("pcss-checker", "pcss computed on a checkerboard (half the pixels), depth-aware upsampling",
                pcssPreset(PcssMode::Regular, false, true)),
      vssmEntry("vssm", "variance soft shadow mapping: exact summed-area table of depth moments, min-max HSM, 5x5 uniform blocker / H=3 adaptive shadow subdivision, contact fallback",
                VssmOptions{}),
      vssmEntry("vssm-uniform", "vssm with uniform subdivision for both kernels (5x5 blocker, 8x8 shadow)",
                vssmPreset(true, 0)),
      vssmEntry("vssm-fp32", "vssm on a plain fp32 summed-area table (fails at large maps: hard case 17)",
                vssmPreset(false, VssmOptions{}.shadowLevels)),
      msmEntry("msm", "moment shadow mapping: hard shadows from the light centre, Hamburger 4MSM over a filter box of a four-moment summed-area table",
               msmPreset(false)),
      msmEntry("msm-soft", "moment soft shadows: PCSS blocker search and filtering from four-moment summed-area tables (4MSM)",
               msmPreset(true)),
      presetEntry("evsm", "exponential variance shadow maps (two exponents, four moments) with vssm's PCSS summed-area penumbra",
                  evsmParams(EvsmOptions{}), EvsmOptions{}, makeExponentialVarianceShadowMaps, TechniqueFamily::SingleMap),
      {"raytrace", "Embree reference with the same light samples as every technique (per sample)", {},
       [](const TechniqueArgs&) { return makeRaytraceSameSamples(); }, TechniqueFamily::ExactPerSample},
      {"raytrace-converged", "Embree reference: visibility from 2048+ stratified light samples per pixel, the shaded image by MIS of light and BRDF to a 1e-3 relative standard error (65536 samples at most), each with its noise",
       raytraceConvergedParams(), makeRaytraceConverged, TechniqueFamily::ExactPerSample},
      {"raytrace-denoised", "1-4 shadow rays per pixel through Embree, temporal accumulation and a penumbra-sized cross-bilateral filter (NRD SIGMA style)",
       denoisedParams(), makeRaytraceDenoised, TechniqueFamily::Denoised},
  };
  return table;
}

const TechniqueInfo& findTechnique(const std::string& name) {
  std::string known;
  for (auto& t : techniqueTable()) {
    if (t.name == name) return t;
    known += (known.empty() ? "" : ", ") + t.name;
  }
  throw Error("technique", "unknown technique '" + name + "' (known: " + known + ")", ExitCode::Usage);
}

std::vector<TechniqueInfo> findTechniques(const std::vector<std::string>& names) {
  std::vector<TechniqueInfo> out;
  for (auto& n : names) out.push_back(findTechnique(n));
  return out;
}

std::unique_ptr<Technique> makeTechnique(const std::string& name, const TechniqueParams& params) {
  return findTechnique(name).make(params);
}

}  // namespace penumbra
