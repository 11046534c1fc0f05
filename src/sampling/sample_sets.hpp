// C++ side of sampling/shaders/sample_sets.h (the light-sample set a pixel uses), in namespace penumbra::shared.
#pragma once
#include "shared/shared.hpp"

namespace penumbra::shared {
#include "sampling/shaders/sample_sets.h"  // NOLINT: shared with GLSL
}  // namespace penumbra::shared
