// The DCS paper's 2D covered-sample modes (sections 7.1, 7.3; src/techniques/dcs/edge_lut.h),
// for dcs_wedge.frag with DCS_COVERAGE naive or lut. Needs common_light.glsl.
#include "techniques/dcs/shaders/dcs_modes.h"
#include "dcs_bindings.h"
#if DCS_COVERAGE != PENUMBRA_DCS_COVERAGE_EXACT
uniform vec3 lightAxisU;  // tangent / half-width: the light's normalised frame (c at the origin)
uniform vec3 lightAxisV;  // bitangent / half-height
uniform float lutExtent;  // the line table covers feet in [-R, R]^2
layout(binding = PENUMBRA_UNIT_DCS_SECTOR_LUT) uniform usamplerCubeArray sectorLut;
layout(binding = PENUMBRA_UNIT_DCS_LINE_LUT) uniform usampler2DArray lineLut;
layout(std430, binding = PENUMBRA_SSBO_DCS_PACKED) readonly buffer DcsPacked { uint dcsPacked[]; };

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

// The edge (a, b) seen from p, projected onto the light's plane in its normalised frame, q0 -> q1
// counter-clockwise around c: the part of the edge between p's plane parallel to the light and
// the light's plane is kept (a part beyond the light, or behind p, separates no path from c to a
// sample). Returns 0 when nothing is left, 1 with (q0, q1), -1 when p lies (nearly) in the
// light's plane, where no projection exists (the caller uses the exact test).
int dcsProjectEdge(vec3 p, vec3 a, vec3 b, vec3 c, out vec2 q0, out vec2 q1) {
  float h = dot(lightNormal, c - p);
  if (abs(h) <= 1e-6 * length(c - p)) return -1;
  // Heights as fractions of p's height: 0 in p's plane, 1 in the light's.
  float ha = dot(lightNormal, a - p) / h, hb = dot(lightNormal, b - p) / h;
  const float lowest = 1e-4;  // keeps projected points finite
  float lo = 0.0, hi = 1.0;
  if (ha < lowest && hb < lowest) return 0;
  if (ha > 1.0 && hb > 1.0) return 0;
  if (ha < lowest) lo = max(lo, (lowest - ha) / (hb - ha));
  if (hb < lowest) hi = min(hi, (lowest - ha) / (hb - ha));
  if (ha > 1.0) lo = max(lo, (ha - 1.0) / (ha - hb));
  if (hb > 1.0) hi = min(hi, (ha - 1.0) / (ha - hb));
  if (lo >= hi) return 0;
  vec3 x0 = mix(a, b, lo), x1 = mix(a, b, hi);
  vec3 y0 = p + (x0 - p) / mix(ha, hb, lo) - c, y1 = p + (x1 - p) / mix(ha, hb, hi) - c;
  q0 = vec2(dot(y0, lightAxisU), dot(y0, lightAxisV));
  q1 = vec2(dot(y1, lightAxisU), dot(y1, lightAxisV));
  float turn = cross2(q0, q1);
  if (turn == 0.0) return 0;  // the line runs through c: it separates c from no sample
  if (turn < 0.0) {
    vec2 t = q0;
    q0 = q1;
    q1 = t;
  }
  return 1;
}

// 32 bits of a 128-bit field starting at bit `first` (zeros past bit 127).
uint dcsBitsFrom(uvec4 m, uint first) {
  uint w = first >> 5u, o = first & 31u;
  uint lo = w < 4u ? m[w] >> o : 0u;
  uint hi = (o != 0u && w + 1u < 4u) ? m[w + 1u] << (32u - o) : 0u;
  return lo | hi;
}

// The covered samples of set `set` as a 128-bit field (bit k: sample k of the set).
uvec4 dcsCoveredField(vec2 q0, vec2 q1, uint set, uint count) {
#if DCS_COVERAGE == PENUMBRA_DCS_COVERAGE_NAIVE
  // A loop over the packed positions: the sector from q0 to q1 and beyond the segment's line.
  uvec4 m = uvec4(0u);
  uint first = set * ((count + 1u) / 2u);
  for (uint k = 0u; k < count; ++k) {
    uint word = dcsPacked[first + k / 2u] >> (16u * (k & 1u));
    vec2 s = vec2(float(word & 255u), float((word >> 8u) & 255u)) / 255.0 * 2.0 - 1.0;
    if (cross2(q0, s) >= 0.0 && cross2(s, q1) >= 0.0 && cross2(q1 - q0, s - q0) < 0.0) m[k >> 5u] |= 1u << (k & 31u);
  }
  return m;
#else
  // M = sector & line (Fig. 8): three fetches and a logical combination.
  uvec4 s0 = texture(sectorLut, vec4(q0, 0.0, float(set)));
  uvec4 s1 = texture(sectorLut, vec4(q1, 0.0, float(set)));
  bool wrap = q0.y <= 0.0 && q1.y >= 0.0;  // the sector holds the +x axis, where angles restart
  uvec4 sector = wrap ? (s1 | ~s0) : (s1 & ~s0);
  vec2 e = q1 - q0;
  vec2 foot = q0 - e * (dot(q0, e) / dot(e, e));
  int size = textureSize(lineLut, 0).x;
  ivec2 t = ivec2(floor((foot / lutExtent + 1.0) * 0.5 * float(size)));
  if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, ivec2(size)))) return uvec4(0u);
  return sector & texelFetch(lineLut, ivec3(t, int(set)), 0);
#endif
}
#endif
