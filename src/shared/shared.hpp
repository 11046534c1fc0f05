// C++ side of the GLSL-shared headers: the GLSL-style `uint`, `vec3` and functions they use, in
// namespace penumbra::shared, and the ground floor (shared.h, numerics.h) in it. A layer's
// GLSL-shared header has its own wrapper that includes this one first, then the header inside
// the namespace (sampling/sample_sets.hpp, shading/shading_shared.hpp, a technique's).
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

namespace penumbra::shared {
using uint = std::uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using glm::abs;
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::exp2;
using glm::floor;
using glm::length;
using glm::max;
using glm::min;
using glm::normalize;
using glm::sqrt;
#include "shared/shared.h"    // NOLINT: shared with GLSL
#include "shared/numerics.h"  // NOLINT: shared with GLSL
}  // namespace penumbra::shared
