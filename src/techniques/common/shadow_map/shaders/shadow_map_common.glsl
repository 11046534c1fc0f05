// The light-sample views of the multi-view shadow-map techniques (src/techniques/shadow_map):
// every map looks along mapAxis from its sample position with the same symmetric square frustum
// (half-angle tangent mapTanHalf), reversed depth z = mapNear / d for view depth d (1 at the near
// plane, 0 at infinity, as the camera's), so a larger stored value is closer: atomicMax on the
// uint bits of a positive float depth is a z-buffer (VWSS Listing 2 uses InterlockedMax alike).
#include "shared/numerics.h"
uniform vec3 mapAxis;
uniform vec3 mapRight;
uniform vec3 mapUp;
uniform float mapTanHalf;
uniform float mapNear;
uniform int mapSize;

// Clip coordinates of p in a view along mapAxis whose eye is `eye` with near plane `near`
// (glClipControl ZERO_TO_ONE: clipped at d < near, never at the far end).
vec4 viewClip(vec3 p, vec3 eye, float near) {
  vec3 r = p - eye;
  return vec4(dot(r, mapRight) / mapTanHalf, dot(r, mapUp) / mapTanHalf, near, dot(r, mapAxis));
}
vec4 mapClip(vec3 p, vec3 eye) { return viewClip(p, eye, mapNear); }

// Texel of normalised device coordinates in a size x size map, as the rasteriser assigns
// fragments (glClipControl GL_UPPER_LEFT flips y): texel (i, j) holds what covers its centre.
ivec2 viewTexel(vec2 ndc, int size) {
  return ivec2(floor(vec2(ndc.x * 0.5 + 0.5, 0.5 - 0.5 * ndc.y) * float(size)));
}

// The inverse for a texel centre: normalised device coordinates.
vec2 viewTexelNdc(ivec2 texel, int size) {
  vec2 uv = (vec2(texel) + 0.5) / float(size);
  return vec2(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
}

// Depth bias. Receiver-plane depth (Isidoro 2006): every tap compares with the depth, along the
// tap's own ray, of the receiver's plane (the G-buffer's face normal), not with the receiver's
// depth at its own texel, so a planar receiver meets itself exactly in a rasterised map at any
// slope (no acne) and needs no large offset (no peter-panning). What remains: biasConstant
// (world units; negative: 4 x the float epsilon of the two positions the depth is computed from,
// shared/numerics.h penumbraSurfaceEpsilon, so the bias follows the numbers' magnitude, not the scene's
// size) plus biasSlope texels of the plane's depth slope, for depths stored off the texel
// centre (vwss's points, pcss's bilinear taps); the slope is the view depth gained per world unit
// of lateral image-plane offset, |n_lateral| / |n . ray| with the ray at unit depth, capped at
// 100 for grazing receivers.
uniform float biasConstant;
uniform float biasSlope;
float depthBias(vec3 o, vec3 n, vec3 eye, float d) {
  vec3 ray = (o - eye) / d;
  float slope = min(length(n - mapAxis * dot(n, mapAxis)) / max(abs(dot(n, ray)), 1e-4), 100.0);
  float constant = biasConstant >= 0.0 ? biasConstant : 4.0 * (penumbraSurfaceEpsilon(o) + penumbraSurfaceEpsilon(eye));
  return constant + biasSlope * slope * d * 2.0 * mapTanHalf / float(mapSize);
}
// The view depth of the plane through o (normal n) along the ray of the view from `eye` through
// normalised device coordinates ndc; `d` (o's own depth) where that ray runs (nearly) along the
// plane, and at most a factor 2 from d.
float planeDepth(vec3 o, vec3 n, vec3 eye, vec2 ndc, float d) {
  vec3 ray = mapAxis + mapTanHalf * (ndc.x * mapRight + ndc.y * mapUp);
  float den = dot(n, ray);
  float t = dot(n, o - eye) / den;
  return abs(den) > 1e-6 && t > 0.0 ? clamp(t, 0.5 * d, 2.0 * d) : d;
}

// True for a float whose exponent is all ones (Inf or NaN), tested on its bits so that no
// compiler assumption about NaN can remove the test (hard case 22).
bool mapNonFinite(vec3 v) {
  return any(equal(floatBitsToUint(v) & 0x7f800000u, uvec3(0x7f800000u)));
}
