// C++ side of shaders/shared.h: gives the GLSL-style `uint`, `vec3` and the functions the header
// uses, and includes it.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

namespace penumbra::shared {
using uint = std::uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using glm::abs;
using glm::cross;
using glm::dot;
using glm::length;
using glm::exp2;
using glm::exp;
using glm::max;
using glm::min;
using glm::sqrt;
using glm::normalize;
using glm::clamp;
#include "shared.h"  // NOLINT: shared with GLSL, see shaders/shared.h
}  // namespace penumbra::shared
