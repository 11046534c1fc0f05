// pcss (src/techniques/pcss): percentage-closer soft shadows (Fernando 2005) with Sterna's
// (2018) sampling: Vogel disk samples (Listing 1) rotated per pixel by interleaved gradient
// noise (Listing 2). One depth map from the light centre (reversed depth z = near / d).
//  1. Blocker search: BLOCKER_SAMPLES taps over the region of the map the light covers seen from
//     the receiver, projected on the plane of the nearest occluder (searchNear, Fernando's near
//     plane); taps nearer than the receiver are blockers; their depths are averaged.
//  2. Penumbra (parallel planes): w = lightHalfSize * (d_receiver - d_blocker) / d_blocker.
//  3. PCF: PCF_SAMPLES taps of the hardware comparison sampler (bilinear, 4 texels each) over
//     the Vogel disk of that radius.
// No blocker: fully lit. A single view: every light sample gets the same shadow factor S, and
// the visibility buffer is S times the mean luminance of the samples above the receiver's
// horizon (textured lights modulate by their average luminance: the single-view approximation).
#include "common_light.glsl"
#include "shadow_map_common.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
layout(binding = PENUMBRA_UNIT_PCSS_DEPTH) uniform sampler2D depthRaw;         // nearest, border 0
layout(binding = PENUMBRA_UNIT_PCSS_COMPARE) uniform sampler2DShadow depthCmp;  // linear, GEQUAL
uniform vec3 eyePosition;
uniform float surfaceOffset;
uniform float lightHalfSize;  // world units: half the light's extent across the axis
uniform float searchNear;     // view depth of the nearest occluder (blocker-search plane)
uniform int blockerSamples;
uniform int pcfSamples;

out vec4 outVisibility;

const float TWO_PI = 6.28318530718;

// Sterna, Listing 2 (Jimenez 2014).
float interleavedGradientNoise(vec2 pixel) {
  return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

// Sterna, Listing 1: sample i of n on the unit disk, rotated by phi.
vec2 vogelDisk(int i, int n, float phi) {
  float r = sqrt(float(i) + 0.5) / sqrt(float(n));
  float theta = float(i) * 2.4 + phi;
  return r * vec2(cos(theta), sin(theta));
}

// Map uv of normalised device coordinates (the rasteriser's texel convention, viewTexel).
vec2 mapUv(vec2 ndc) { return vec2(ndc.x * 0.5 + 0.5, 0.5 - 0.5 * ndc.y); }

// One uv unit per this many world units at view depth d.
float worldPerUv(float d) { return 2.0 * d * mapTanHalf; }

float pcssShadow(vec3 o, vec3 n) {
  vec4 c = mapClip(o, lightPosition);
  if (!(c.w > mapNear)) return 1.0;
  float receiver = biasedDepth(o, n, lightPosition, c.w);
  if (!(receiver > mapNear)) return 1.0;
  float zReceiver = mapNear / receiver;
  vec2 uv = mapUv(c.xy / c.w);
  float phi = TWO_PI * interleavedGradientNoise(gl_FragCoord.xy);
  // 1. Blocker search over the light's footprint, seen from the receiver, on the nearest
  //    occluder's plane (Fernando's LIGHT_SIZE_UV * (z_receiver - near) / z_receiver).
  float near = min(searchNear, receiver);
  float searchRadius = lightHalfSize * (receiver - near) / receiver / worldPerUv(near);
  searchRadius = min(searchRadius, 0.5);
  float blockerSum = 0.0, blockers = 0.0;
  for (int i = 0; i < blockerSamples; ++i) {
    float z = texture(depthRaw, uv + searchRadius * vogelDisk(i, blockerSamples, phi)).r;
    if (z > zReceiver) {  // nearer to the light than the receiver
      blockerSum += mapNear / z;
      blockers += 1.0;
    }
  }
  if (blockers == 0.0) return 1.0;
  float blocker = blockerSum / blockers;
  // 2. Penumbra width on the receiver (parallel planes), as a uv radius at the receiver.
  float filterRadius = lightHalfSize * (receiver - blocker) / blocker / worldPerUv(receiver);
  // At least the bilinear footprint of one texel.
  filterRadius = max(filterRadius, 0.5 / float(mapSize));
  // 3. PCF with the comparison sampler: lit where zReceiver >= stored.
  float lit = 0.0;
  for (int i = 0; i < pcfSamples; ++i)
    lit += texture(depthCmp, vec3(uv + filterRadius * vogelDisk(i, pcfSamples, phi), zReceiver));
  return lit / float(pcfSamples);
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 p = texelFetch(gPosition, px, 0);
  if (p.w == 0.0) { outVisibility = vec4(0.0); return; }
  vec3 n = texelFetch(gNormal, px, 0).xyz;
  uint base = pixelSampleBase(px);
  vec3 luminance = vec3(0.0);
  for (uint k = 0u; k < sampleCount; ++k)
    if (aboveHorizon(p.xyz, n, samplePositions[base + k].xyz)) luminance += sampleLuminance[base + k].rgb;
  if (luminance == vec3(0.0)) { outVisibility = vec4(0.0, 0.0, 0.0, 1.0); return; }
  vec3 o = penumbraShadowOrigin(p.xyz, n, eyePosition, surfaceOffset);
  outVisibility = vec4(luminance / float(sampleCount) * pcssShadow(o, n), 1.0);
}
