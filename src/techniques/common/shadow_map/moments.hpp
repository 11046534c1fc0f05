// C++ side of techniques/common/shadow_map/shaders/moments.h (the 4MSM reconstruction), in namespace penumbra::shared.
#pragma once
#include "shared/shared.hpp"

namespace penumbra::shared {
#include "techniques/common/shadow_map/shaders/moments.h"  // NOLINT: shared with GLSL
}  // namespace penumbra::shared
