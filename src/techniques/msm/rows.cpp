// The msm folder's rows in the table of techniques (registry.h).
#include "techniques/msm/msm.h"
#include "techniques/registry.h"

namespace penumbra {

namespace {
TechniqueInfo msmRow(std::string name, std::string description, bool soft, bool translucent = false) {
  MsmOptions preset;
  preset.soft = soft;
  preset.translucent = translucent;
  return presetRow(std::move(name), std::move(description), TechniqueFamily::SingleMap, msmParams(preset), preset,
                   makeMomentShadowMapping);
}
}  // namespace

std::vector<TechniqueInfo> msmRows() {
  return {
      msmRow("msm",
             "moment shadow mapping: hard shadows from the light centre, Hamburger 4MSM over a filter box of a "
             "four-moment summed-area table",
             false),
      msmRow("msm-soft",
             "moment soft shadows: PCSS blocker search and filtering from four-moment summed-area tables (4MSM)", true),
      msmRow("msm-translucent",
             "msm-soft with translucent occluders: semi-opaque surfaces blend their moments by their opacity (the "
             "filtered competitor of dcs's product)",
             true, true),
  };
}

}  // namespace penumbra
