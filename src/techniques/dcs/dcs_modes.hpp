// C++ side of techniques/dcs/shaders/dcs_modes.h (dcs's modes and a counter's transmittance), in namespace
// penumbra::shared.
#pragma once
#include "shared/shared.hpp"

namespace penumbra::shared {
#include "techniques/dcs/shaders/dcs_modes.h"  // NOLINT: shared with GLSL
}  // namespace penumbra::shared
