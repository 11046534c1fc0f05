// Shared by the pcss passes (src/techniques/pcss): Fernando 2005's three steps with Sterna 2018's
// sampling. Reversed depth z = near / d in the light centre's map (shadow_map_common.glsl).
#include "shared/numerics.h"
#include "single_view_bindings.h"
#include "common_light.glsl"
#include "shadow_map_common.glsl"
#include "light_rays.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
layout(binding = PENUMBRA_UNIT_PCSS_DEPTH) uniform sampler2D depthRaw;         // nearest, border 0
layout(binding = PENUMBRA_UNIT_PCSS_COMPARE) uniform sampler2DShadow depthCmp;  // linear, GEQUAL
uniform vec3 eyePosition;
uniform float lightHalfSize;  // world units: half the side of the light's equal-area square
uniform float searchNear;     // view depth of the nearest occluder (blocker-search plane)
uniform int blockerSamples;
uniform int pcfSamples;
uniform float kernelScale;    // Sterna 2.2: the penumbra-mask pass searches 1.2-1.6x wider

const float TWO_PI = 6.28318530718;

// interleavedGradientNoise (Sterna, Listing 2) is light_rays.glsl's; checkerboarded passes
// stretch y by 4 (Listing 7).

// Sterna, Listing 1: sample i of n on the unit disk, rotated by phi.
vec2 vogelDisk(int i, int n, float phi) {
  float r = sqrt(float(i) + 0.5) / sqrt(float(n));
  float theta = float(i) * 2.4 + phi;
  return r * vec2(cos(theta), sin(theta));
}

// Map uv of normalised device coordinates (the rasteriser's texel convention, viewTexel).
vec2 mapUv(vec2 ndc) { return vec2(ndc.x * 0.5 + 0.5, 0.5 - 0.5 * ndc.y); }

// World units per uv unit at view depth d.
float worldPerUv(float d) { return 2.0 * d * mapTanHalf; }

// A surface point seen from the light centre: its map uv, biased depth, reversed depth, and its
// plane (for the receiver-plane depth of each tap, shadow_map_common.glsl planeDepth).
struct Receiver {
  vec2 uv;
  float depth;  // biased view depth
  float z;      // mapNear / depth
  bool inView;  // false: on or behind the light's plane, or the bias ate it (lit)
  vec3 o, n;    // evaluation point and face normal
  float d, bias;
};

// Reversed depth of the receiver's plane, biased, along the ray through map uv.
float tapZ(Receiver r, vec2 uv) {
  float depth = planeDepth(r.o, r.n, lightPosition, vec2(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0), r.d) - r.bias;
  return depth > mapNear ? mapNear / depth : 3.0e38;
}

Receiver receiverOf(ivec2 px, out vec3 p, out vec3 n) {
  Receiver r;
  vec4 g = texelFetch(gPosition, px, 0);
  p = g.xyz;
  n = texelFetch(gNormal, px, 0).xyz;
  vec3 o = penumbraShadowOrigin(p, n, eyePosition);
  vec4 c = mapClip(o, lightPosition);
  r.o = o;
  r.n = n;
  r.d = c.w;
  r.inView = c.w > mapNear;
  r.bias = r.inView ? depthBias(o, n, lightPosition, c.w) : 0.0;
  r.depth = c.w - r.bias;
  r.inView = r.inView && r.depth > mapNear;
  r.z = r.inView ? mapNear / r.depth : 0.0;
  r.uv = r.inView ? mapUv(c.xy / c.w) : vec2(0.0);
  return r;
}

// Step 1 (blocker search): the mean view depth of the taps nearer to the light than the
// receiver over the light's footprint seen from the receiver on the nearest occluder's plane
// (Fernando's LIGHT_SIZE_UV * (z_receiver - near) / z_receiver), scaled; -1 if none.
float searchRadius(Receiver r) {
  float near = min(searchNear, r.depth);
  return min(kernelScale * lightHalfSize * (r.depth - near) / r.depth / worldPerUv(near), 0.5);
}
// One blocker-search tap: a texel nearer than the receiver plane there adds its view depth.
void blockerTap(Receiver r, vec2 uv, inout float sum, inout float count) {
  float z = texture(depthRaw, uv).r;
  if (z > tapZ(r, uv)) {
    sum += mapNear / z;
    count += 1.0;
  }
}
float averageBlockerDepth(Receiver r, float phi) {
  float radius = searchRadius(r);
  float sum = 0.0, count = 0.0;
  for (int i = 0; i < blockerSamples; ++i) blockerTap(r, r.uv + radius * vogelDisk(i, blockerSamples, phi), sum, count);
  return count > 0.0 ? sum / count : -1.0;
}

// Step 2 (parallel planes): the penumbra's half-width on the receiver, as a uv radius, at
// least the bilinear footprint of a texel.
float penumbraRadius(Receiver r, float blocker) {
  return max(lightHalfSize * (r.depth - blocker) / blocker / worldPerUv(r.depth), 0.5 / float(mapSize));
}

// Step 3: PCF with the comparison sampler (4 texels a tap, bilinear).
float litTap(Receiver r, vec2 uv) { return texture(depthCmp, vec3(uv, tapZ(r, uv))); }
float percentageCloser(Receiver r, float radius, float phi) {
  float lit = 0.0;
  for (int i = 0; i < pcfSamples; ++i) lit += litTap(r, r.uv + radius * vogelDisk(i, pcfSamples, phi));
  return lit / float(pcfSamples);
}

// Fernando's dense kernels: every texel of the square of half-size `radius` (uv) around the
// receiver, thinned to at most DENSE_MAX x DENSE_MAX taps (evenly spaced) for huge kernels.
#define DENSE_MAX 32
void denseGrid(Receiver r, float radius, out vec2 origin, out vec2 step, out int count) {
  float texels = max(2.0 * radius * float(mapSize), 1.0);
  count = int(min(ceil(texels), float(DENSE_MAX)));
  step = vec2(2.0 * radius / float(count));
  origin = r.uv - vec2(radius) + 0.5 * step;
}
float averageBlockerDepthDense(Receiver r) {
  vec2 origin, step;
  int count;
  denseGrid(r, searchRadius(r), origin, step, count);
  float sum = 0.0, blockers = 0.0;
  for (int j = 0; j < count; ++j)
    for (int i = 0; i < count; ++i) blockerTap(r, origin + step * vec2(i, j), sum, blockers);
  return blockers > 0.0 ? sum / blockers : -1.0;
}
float percentageCloserDense(Receiver r, float radius) {
  vec2 origin, step;
  int count;
  denseGrid(r, radius, origin, step, count);
  float lit = 0.0;
  for (int j = 0; j < count; ++j)
    for (int i = 0; i < count; ++i) lit += litTap(r, origin + step * vec2(i, j));
  return lit / float(count * count);
}

// Mean luminance L_k of the samples above the receiver's horizon over N: a single view gives
// every sample the same shadow factor (textured lights modulate by their mean luminance).
vec3 horizonLuminance(ivec2 px, vec3 p, vec3 n) {
  uint base = pixelSampleBase(px);
  vec3 luminance = vec3(0.0);
  for (uint k = 0u; k < sampleCount; ++k)
    if (aboveHorizon(p, n, samplePositions[base + k].xyz)) luminance += sampleLuminance[base + k].rgb;
  return luminance / float(sampleCount);
}
