// Lighting stage of the multi-view shadow-map techniques (mvr, vwss, reproject): per light
// sample, shadow mapping in that sample's map with PCF (PCF_TAPS: 1, the VWSS paper's 5 (centre
// and the 4 neighbours) or 3 x 3 = 9 nearest-texel compares, averaged), at the same evaluation
// point as every technique and the reference (shared/numerics.h penumbraShadowOrigin). The per-sample
// results go to the per-sample array and, weighted by the sample luminance L_i, to the
// visibility buffer of DCS eq. 2 (textured lights are exact per sample).
// Depth bias (shadow_map_common.glsl: receiver-plane depth per tap, plus depthBias), applied
// here after the maps are made (fragment reprojection section 3.1.1: bias after reprojection).
#include "shared/numerics.h"
#include "shadow_map_bindings.h"
#include "common_light.glsl"
#include "shadow_map_common.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
#ifdef UINT_MAPS
layout(binding = PENUMBRA_UNIT_SHADOW_MAPS) uniform usampler2DArray shadowMaps;
float storedDepth(ivec3 t) { return uintBitsToFloat(texelFetch(shadowMaps, t, 0).r); }
#else
layout(binding = PENUMBRA_UNIT_SHADOW_MAPS) uniform sampler2DArray shadowMaps;  // DEPTH32F
float storedDepth(ivec3 t) { return texelFetch(shadowMaps, t, 0).r; }
#endif
#ifdef SEMI_OPAQUE
// Semi-opaque surfaces of each map texel (src/techniques/common/shadow_map/shaders/shadow_map_transmittance.frag): a count and
// K entries (reversed depth, opacity in the low 8 bits) a map.
layout(binding = PENUMBRA_UNIT_SEMI_COUNT) uniform usampler2DArray semiCount;
layout(binding = PENUMBRA_UNIT_SEMI_LAYERS) uniform usampler2DArray semiLayers;
uniform int semiSlots;
// Product of 1 - opacity of the semi-opaque surfaces of texel t nearer to the sample than the
// receiver (reversed depth zReceiver), as the reference multiplies along its ray.
float semiOpaqueTransmittance(ivec3 t, float zReceiver) {
  int n = min(int(texelFetch(semiCount, t, 0).r), semiSlots);
  float transmittance = 1.0;
  for (int i = 0; i < n; ++i) {
    uint e = texelFetch(semiLayers, ivec3(t.xy, t.z * semiSlots + i), 0).r;
    if (uintBitsToFloat(e & 0xFFFFFF00u) > zReceiver) transmittance *= 1.0 - float(e & 0xFFu) / 255.0;
  }
  return transmittance;
}
#endif
#ifdef PER_SAMPLE_OUT
layout(binding = PENUMBRA_IMAGE_SAMPLE_VIS, r32f) uniform writeonly image2DArray sampleVisibility;
#endif
uniform vec3 eyePosition;  // the camera

out vec4 outVisibility;

#if PCF_TAPS == 9
const int TAPS = 9;
const ivec2 tapOffset[9] = ivec2[](ivec2(0, 0), ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1),
                                   ivec2(-1, -1), ivec2(1, -1), ivec2(-1, 1), ivec2(1, 1));
#elif PCF_TAPS == 5
const int TAPS = 5;
const ivec2 tapOffset[5] = ivec2[](ivec2(0, 0), ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
#else
const int TAPS = 1;
const ivec2 tapOffset[1] = ivec2[](ivec2(0, 0));
#endif

// Fraction of the taps around o's texel in map `layer` that see o from the sample at x; each tap
// compares with the receiver plane's depth along its own ray (shadow_map_common.glsl).
float shadowTest(vec3 o, vec3 n, vec3 x, int layer) {
  vec4 c = mapClip(o, x);
  if (!(c.w > mapNear)) return 1.0;  // in or behind the sample's plane: nothing in between
  float bias = depthBias(o, n, x, c.w);
  ivec2 t = viewTexel(c.xy / c.w, mapSize);
  float lit = 0.0;
  for (int i = 0; i < TAPS; ++i) {
    ivec2 q = t + tapOffset[i];
    // Outside the map: nothing was drawn there (the frustum holds every receiver, see
    // shadow_map/maps.h computeMapFrame), lit.
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(mapSize)))) {
      lit += 1.0;
      continue;
    }
    float receiver = planeDepth(o, n, x, viewTexelNdc(q, mapSize), c.w) - bias;
    // Lit iff the stored (reversed) depth is at most the receiver's: nothing nearer to the sample.
    float zReceiver = receiver > 0.0 ? mapNear / receiver : 3.0e38;
    float tap = storedDepth(ivec3(q, layer)) <= zReceiver ? 1.0 : 0.0;
#ifdef SEMI_OPAQUE
    if (tap > 0.0) tap *= semiOpaqueTransmittance(ivec3(q, layer), zReceiver);
#endif
    lit += tap;
  }
  return lit / float(TAPS);
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 p = texelFetch(gPosition, px, 0);
  if (p.w == 0.0) { outVisibility = vec4(0.0); return; }
  vec3 n = texelFetch(gNormal, px, 0).xyz;
  vec3 o = penumbraShadowOrigin(p.xyz, n, eyePosition);
  uint base = pixelSampleBase(px);
  vec3 v = vec3(0.0);
  for (uint k = 0u; k < sampleCount; ++k) {
    vec3 x = samplePositions[base + k].xyz;
    float visible = aboveHorizon(p.xyz, n, x) ? shadowTest(o, n, x, int(base + k)) : 0.0;
#ifdef PER_SAMPLE_OUT
    imageStore(sampleVisibility, ivec3(px, int(k)), vec4(visible));
#endif
    v += sampleLuminance[base + k].rgb * visible;
  }
  outVisibility = vec4(v / float(sampleCount), 1.0);
}
