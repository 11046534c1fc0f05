// The evsm folder's row in the table of techniques (registry.h).
#include "techniques/evsm/evsm.h"
#include "techniques/registry.h"

namespace penumbra {

std::vector<TechniqueInfo> evsmRows() {
  return {presetRow(
      "evsm", "exponential variance shadow maps (two exponents, four moments) with vssm's PCSS summed-area penumbra",
      TechniqueFamily::SingleMap, evsmParams(EvsmOptions{}), EvsmOptions{}, makeExponentialVarianceShadowMaps)};
}

}  // namespace penumbra
