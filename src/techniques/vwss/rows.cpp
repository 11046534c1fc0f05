// The vwss folder's rows in the table of techniques (registry.h).
#include "techniques/registry.h"
#include "techniques/vwss/vwss.h"

namespace penumbra {

namespace {
TechniqueInfo vwssRow(std::string name, std::string description, VwssMode mode) {
  return presetRow(std::move(name), std::move(description), TechniqueFamily::MultiView, vwssParams(mode), mode,
                   makeViewWarpedSoftShadows);
}
}  // namespace

std::vector<TechniqueInfo> vwssRows() {
  return {
      vwssRow("vwss", "view-warped soft shadows: points from one enlarged central view, compute splat (buffered)",
              VwssMode::Buffered),
      vwssRow("vwss-unbuffered", "vwss splatting from the point-generation fragment shader (no point buffer)",
              VwssMode::Unbuffered),
      vwssRow("vwss-graphics", "vwss's points drawn as GL_POINTS, a draw per map, depth-tested (graphics pipeline)",
              VwssMode::Graphics),
  };
}

}  // namespace penumbra
