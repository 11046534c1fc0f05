// C++ side of shading/shaders/shading.h (the shading math the shaders and the CPU reference share), in namespace
// penumbra::shared.
#pragma once
#include "shared/shared.hpp"

namespace penumbra::shared {
#include "shading/shaders/shading.h"     // NOLINT: shared with GLSL
#include "shading/shaders/alpha_test.h"  // NOLINT: shared with GLSL
}  // namespace penumbra::shared
