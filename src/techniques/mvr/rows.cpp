// The mvr folder's rows in the table of techniques (registry.h).
#include "techniques/mvr/mvr.h"
#include "techniques/registry.h"

namespace penumbra {

std::vector<TechniqueInfo> mvrRows() {
  return {
      presetRow("mvr",
                "multi-view rasterisation: a depth map per light sample, one draw each, PCF (VWSS paper's reference)",
                TechniqueFamily::MultiView, mvrParams(), false, makeMultiViewRasterisation),
      presetRow("mvr-layered", "mvr in one instanced draw, a geometry shader routing instances to map layers",
                TechniqueFamily::MultiView, mvrParams(), true, makeMultiViewRasterisation),
  };
}

}  // namespace penumbra
