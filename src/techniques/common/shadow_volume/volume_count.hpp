// C++ side of techniques/common/shadow_volume/shaders/volume_count.h (the exact shadow-volume count), in namespace
// penumbra::shared.
#pragma once
#include "shared/shared.hpp"

namespace penumbra::shared {
#include "techniques/common/shadow_volume/shaders/volume_count.h"  // NOLINT: shared with GLSL
}  // namespace penumbra::shared
