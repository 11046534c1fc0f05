// The sRGB transfer functions (IEC 61966-2-1), for 8-bit images and sRGB-encoded textures.
#pragma once

#include <cmath>

namespace penumbra {

// sRGB-encoded value in [0, 1] -> linear.
inline float srgbToLinear(float s) { return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f); }

// Linear value in [0, 1] -> sRGB-encoded.
inline float linearToSrgb(float v) { return v <= 0.0031308f ? v * 12.92f : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f; }

}  // namespace penumbra
