// The pcss folder's rows in the table of techniques (registry.h): pcss and its presets.
#include "techniques/pcss/pcss.h"
#include "techniques/registry.h"

namespace penumbra {

namespace {
TechniqueInfo pcssRow(std::string name, std::string description, PcssOptions preset) {
  return presetRow(std::move(name), std::move(description), TechniqueFamily::SingleMap, pcssParams(preset), preset,
                   makePercentageCloserSoftShadows);
}
PcssOptions withContact(PcssOptions o) {
  o.contact.enabled = true;
  return o;
}
}  // namespace

std::vector<TechniqueInfo> pcssRows() {
  return {
      pcssRow("pcss",
              "percentage-closer soft shadows, one map from the light centre, Vogel disk + noise (Sterna: 32 blocker, "
              "16 PCF samples)",
              pcssPreset(PcssMode::Regular, false, false)),
      pcssRow("pcss-ultra", "pcss with the 'Ultra' preset the VWSS paper compares with (64 blocker, 96 PCF samples)",
              pcssPreset(PcssMode::Regular, true, false)),
      pcssRow("pcss-mask", "pcss with Sterna's quarter-resolution blurred penumbra mask (kernel scale 1.4)",
              pcssPreset(PcssMode::PenumbraMask, false, false)),
      pcssRow(
          "pcss-minfilter",
          "pcss with Sterna's min filter: blocker depth from the separable nearest-depth filter of the map, blurred",
          pcssPreset(PcssMode::MinFilter, false, false)),
      pcssRow("pcss-dense",
              "pcss as Fernando's original: every texel of the blocker-search and filter kernels (at most 32x32)",
              pcssPreset(PcssMode::Dense, false, false)),
      pcssRow("pcss-checker", "pcss computed on a checkerboard (half the pixels), depth-aware upsampling",
              pcssPreset(PcssMode::Regular, false, true)),
      pcssRow("pcss-contact",
              "pcss with contact shadows multiplied in (a short screen-space march towards the light samples)",
              withContact(pcssPreset(PcssMode::Regular, false, false))),
      pcssRow("pcss-fixed",
              "pcss without the blocker search: the search radius as every pixel's kernel (Sterna's regular shadow "
              "mask; not contact-hardening)",
              pcssPreset(PcssMode::Fixed, false, false)),
  };
}

}  // namespace penumbra
