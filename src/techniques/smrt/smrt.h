// `smrt`: shadow-map ray tracing, the area-light soft shadows Unreal Engine 5's virtual shadow
// maps ([UE-VSM]) and Blender EEVEE since 4.2 ([EEVEE-Shadows]) ship: per pixel a few rays
// towards points of the light, each marched in a few steps through one depth map from the light
// centre, with a heuristic for what lies behind the map's single layer
// (src/techniques/smrt/shaders/smrt_resolve.frag). Written from the engines' documentation, no
// engine's code. The map is one high-resolution map (no virtual paging: our images are small).
#pragma once

#include <memory>
#include <vector>

#include "pipeline/technique.h"
#include "techniques/common/shadow_map/contact.h"

namespace penumbra {

struct SmrtOptions {
  int rays = 7;               // UE 5 r.Shadow.Virtual.SMRT.RayCountLocal
  int steps = 8;              // UE 5 r.Shadow.Virtual.SMRT.SamplesPerRayLocal
  double spacing = 2.0;       // steps at ((s + offset) / steps)^spacing of the ray: denser near the receiver (ours)
  bool extrapolate = true;    // the occluder-extrapolation rule (smrt_resolve.frag)
  double slope = 1.0;         // its depth slope per lateral unit (ours: UE's cvar has other units)
  double thickness = 0.0;     // assumed occluder thickness behind the layer, relative to its depth
  double maxRayAngle = 0.03;  // radians seen from the light centre (UE 5 MaxRayAngleFromLight); 0: none
  bool jitter = true;         // per-pixel rotation of the rays' samples and offset of their steps
  int mapSize = 2048;         // the one map's resolution
  shadow_map::ContactOptions contact;  // contact shadows multiplied in (smrt-contact)
};

// The parameters of a preset, its values their defaults: the map ones of common/shadow_map/maps.h
// (map 2048 here), rays, steps, spacing, extrapolate, slope, thickness, max-ray-angle, jitter.
std::vector<ParamSpec> smrtParams(const SmrtOptions& preset);
std::unique_ptr<Technique> makeShadowMapRayTracing(const TechniqueArgs& args, SmrtOptions preset);

}  // namespace penumbra
