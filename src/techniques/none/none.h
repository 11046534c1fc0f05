// `none`: unshadowed.
#pragma once

#include <memory>

#include "pipeline/technique.h"

namespace penumbra {
std::unique_ptr<Technique> makeUnshadowed();
}  // namespace penumbra
