// The reproject folder's rows in the table of techniques (registry.h).
#include "techniques/registry.h"
#include "techniques/reproject/reproject.h"

namespace penumbra {

std::vector<TechniqueInfo> reprojectRows() {
  return {
      presetRow("reproject", "fragment reprojection: the central z-buffered map reprojected into every map (atomics)",
                TechniqueFamily::MultiView, reprojectParams(), true, makeFragmentReprojection),
      presetRow("reproject-unsync", "fragment reprojection without synchronisation (last writer wins)",
                TechniqueFamily::MultiView, reprojectParams(), false, makeFragmentReprojection),
  };
}

}  // namespace penumbra
