// `pcss`: percentage-closer soft shadows (Fernando 2005) with the sampling of "Contact-hardening
// soft shadows made fast" (Sterna 2018): Vogel disk samples rotated per pixel by interleaved
// gradient noise, hardware comparison PCF. One depth map from the light centre; a single view,
// so one shadow factor for every light sample (shaders/pcss_resolve.frag).
#pragma once

#include <memory>

#include "pipeline/technique.h"

namespace penumbra {

struct PcssPreset {
  int blockerSamples;
  int pcfSamples;
};
// Sterna's Table 1 configuration (32-sample blocker search, 16-sample PCF) and the "Ultra" of
// shipping games that the VWSS paper compares with (64 and 96).
inline constexpr PcssPreset kPcssSterna{32, 16};
inline constexpr PcssPreset kPcssUltra{64, 96};

// Parameters (besides the map ones of shadow_map/maps.h): blocker-samples, pcf-samples.
// Semi-opaque occluders are drawn into the map as opaque (counted: statistic
// "semi-opaque triangles as opaque").
std::unique_ptr<Technique> makePercentageCloserSoftShadows(const TechniqueParams& params, PcssPreset preset);

}  // namespace penumbra
