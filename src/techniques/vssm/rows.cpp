// The vssm folder's rows in the table of techniques (registry.h): vssm and its presets.
#include "techniques/registry.h"
#include "techniques/vssm/vssm.h"

namespace penumbra {

namespace {
TechniqueInfo vssmRow(std::string name, std::string description, VssmOptions preset) {
  return presetRow(std::move(name), std::move(description), TechniqueFamily::SingleMap, vssmParams(preset), preset,
                   makeVarianceSoftShadowMapping);
}
VssmOptions vssmPreset(bool exactSat, int shadowLevels) {
  VssmOptions o;
  o.exactSat = exactSat;
  o.shadowLevels = shadowLevels;
  return o;
}
}  // namespace

std::vector<TechniqueInfo> vssmRows() {
  return {
      vssmRow("vssm",
              "variance soft shadow mapping: exact summed-area table of depth moments, min-max HSM, 5x5 uniform "
              "blocker / H=3 adaptive shadow subdivision, contact fallback",
              VssmOptions{}),
      vssmRow("vssm-uniform", "vssm with uniform subdivision for both kernels (5x5 blocker, 8x8 shadow)",
              vssmPreset(true, 0)),
      vssmRow("vssm-fp32", "vssm on a plain fp32 summed-area table (fails at large maps: hard case 17)",
              vssmPreset(false, VssmOptions{}.shadowLevels)),
  };
}

}  // namespace penumbra
