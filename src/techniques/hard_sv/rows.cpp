// The hard_sv folder's row in the table of techniques (registry.h).
#include "techniques/common/shadow_volume/shadow_volume.h"
#include "techniques/hard_sv/hard_sv.h"
#include "techniques/registry.h"

namespace penumbra {

std::vector<TechniqueInfo> hardSvRows() {
  return {{"hard-sv",
           "hard shadows from the light centre, z-fail shadow volumes (float counter)",
           {bandBytesParam()},
           [](const TechniqueArgs& a) { return makeHardShadowVolumes(readBandBytes(a)); },
           TechniqueFamily::Hard}};
}

}  // namespace penumbra
