// The dcs folder's rows in the table of techniques (registry.h): dcs and its presets; and its
// edge LUT as a pattern table that `penumbra lut` writes.
#include "techniques/dcs/dcs.h"
#include "techniques/dcs/edge_lut.h"
#include "techniques/registry.h"

namespace penumbra {

namespace {
TechniqueInfo dcsRow(std::string name, std::string description, SilhouetteMode silhouettes, dcs::OpacityMode opacity,
                     int coverage) {
  DcsOptions preset;
  preset.silhouettes = silhouettes;
  preset.opacity = opacity;
  preset.coverage = coverage;
  return {std::move(name), std::move(description), dcsParams(preset),
          [](const TechniqueArgs& a) { return makeDepthComplexitySampling(readDcsOptions(a)); },
          TechniqueFamily::ExactPerSample};
}
}  // namespace

std::vector<TechniqueInfo> dcsRows() {
  using dcs::OpacityMode;
  return {
      dcsRow("dcs",
             "depth complexity sampling: per-sample occluder counts, accurate silhouettes (exact; semi-opaque layers "
             "multiply)",
             SilhouetteMode::Accurate, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_EXACT),
      dcsRow("dcs-standard", "depth complexity sampling with standard silhouettes (from the light centre)",
             SilhouetteMode::Standard, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_EXACT),
      dcsRow("dcs-sum", "depth complexity sampling, semi-opaque occluders as the paper's sum of opacities",
             SilhouetteMode::Accurate, OpacityMode::Sum, PENUMBRA_DCS_COVERAGE_EXACT),
      dcsRow("dcs-naive", "dcs with the paper's covered-sample loop over 8-bit packed positions (approximate)",
             SilhouetteMode::Accurate, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_NAIVE),
      dcsRow("dcs-lut", "dcs with the paper's edge LUT (cube-map sectors & line table, approximate)",
             SilhouetteMode::Accurate, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_LUT),
  };
}

PatternTable dcsEdgeLutTable() {
  return {"edge",
          "dcs",
          dcs::edgeLutSupports,
          dcs::unitLight,
          dcs::edgeLutFileName,
          [](const LightSampleSet& samples, const std::string& path, int cube, int line) {
            dcs::writeEdgeLut(path, dcs::buildEdgeLut(dcs::normalisedSamples(samples), samples.count, samples.setCount,
                                                      {cube, line}));
          }};
}

}  // namespace penumbra
