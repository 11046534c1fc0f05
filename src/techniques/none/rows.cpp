// The none folder's row in the table of techniques (registry.h).
#include "techniques/none/none.h"
#include "techniques/registry.h"

namespace penumbra {

std::vector<TechniqueInfo> noneRows() {
  return {{"none",
           "unshadowed direct lighting",
           {},
           [](const TechniqueArgs&) { return makeUnshadowed(); },
           TechniqueFamily::Hard}};
}

}  // namespace penumbra
