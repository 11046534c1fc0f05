// `pcss`: percentage-closer soft shadows (Fernando 2005) with the improvements of "Contact-
// hardening soft shadows made fast" (Sterna 2018): Vogel disk samples rotated per pixel by
// interleaved gradient noise, hardware comparison PCF, and the cheaper penumbra estimates: the
// quarter-resolution blurred penumbra mask (2.2), the min filter (2.3), and checkerboard
// rendering (3). One depth map from the light centre; a single view, so one shadow factor for
// every light sample (src/techniques/pcss/shaders/pcss_*.frag).
#pragma once

#include <memory>

#include "pipeline/technique.h"
#include "techniques/common/shadow_map/contact.h"

namespace penumbra {

enum class PcssMode {
  Regular,       // blocker search per pixel (Sterna's "regular CHSS")
  PenumbraMask,  // blocker search at quarter resolution, blurred, read by the shadow pass
  MinFilter,     // blocker depth from the separable min (nearest) filter of the map, blurred
  Fixed,         // no blocker search: the search radius as the kernel (not contact-hardening)
  Dense,         // Fernando's original: every texel of both kernels (at most 32 x 32)
};

struct PcssOptions {
  PcssMode mode = PcssMode::Regular;
  int blockerSamples = 32, pcfSamples = 16;  // Sterna's Table 1 (mask: 32, shadow: 16)
  bool checkerboard = false;
  double kernelScale = 1.0;            // blocker-search scale (penumbra mask: 1.4, Sterna's 1.2-1.6)
  bool noBlockerOne = false;           // penumbra mask: the largest radius, not 0, where nothing blocks
  bool blur = true;                    // penumbra mask / min filter: the 7x7 Gaussian (sigma 3)
  int minRadius = 0;                   // min filter: window half-size in texels; 0: from the light size
  shadow_map::ContactOptions contact;  // contact shadows multiplied in (pcss-contact)
};

// Presets: Sterna (32 blocker-search samples, 16 PCF) and the "Ultra" of shipping games the
// VWSS paper compares with (64 and 96).
PcssOptions pcssPreset(PcssMode mode, bool ultra, bool checkerboard);

// The parameters of a preset, its values their defaults: the map ones of common/shadow_map/maps.h,
// blocker-samples, pcf-samples, checkerboard; kernel-scale, no-blocker-one (mask), blur (mask,
// min filter), min-radius (min filter). Semi-opaque occluders are drawn into the map as opaque
// (statistic "semi-opaque triangles as opaque").
std::vector<ParamSpec> pcssParams(const PcssOptions& preset);
std::unique_ptr<Technique> makePercentageCloserSoftShadows(const TechniqueArgs& args, PcssOptions preset);

}  // namespace penumbra
