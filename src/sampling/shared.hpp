// C++ side of shaders/shared.h: gives the GLSL-style `uint` and includes the shared header.
#pragma once
#include <cstdint>

namespace penumbra::shared {
using uint = std::uint32_t;
#include "shared.h"  // NOLINT: shared with GLSL, see shaders/shared.h
}  // namespace penumbra::shared
