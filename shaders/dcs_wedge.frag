// Depth-complexity update of one edge at one pixel (DCS Algorithm 1), for the samples of this
// pass, into float-base packed counters (eq. 7-10): sample j of the pass is digit j % DIGITS of
// channel (j / DIGITS) % 4 of target j / (4 * DIGITS); adding delta * DCS_BASE^digit updates it.
// Each fragment's contribution has one sign for all its samples. Positive (outer) and negative
// (inner) updates are blended in one pass, in any order: the packed value is an integer below
// 2^24 in magnitude at every step (the bound keeps every partial digit sum inside (-B, B)), so
// float addition is exact and a digit that is negative for a while borrows and repays exactly.
// The paper's outer-before-inner batching (section 4.3) is needed for unsigned integers only.
// The checksum target gets (the sum of all updates, the positive updates): its second channel,
// started at D(c) + bias, bounds every counter of the pixel at every step (adaptive sampling,
// section 5.3; dcs.cpp checks it after the pass).
// BOUND: instead, add the positive updates that cover any of the pixel's samples into one R32F
// target, before any counter exists (the first frame of a light).
#include "common_light.glsl"
#include "common_dcs.glsl"
#include "common_dcs_lut.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
uniform vec3 eyePosition;
uniform float lightRadius;  // bounding radius of the light around its centre
uniform vec3 lightCorners[8];  // dcs.cpp lightCorners(): a planar light's 4 in cyclic order
uniform int lightCornerCount;
uniform uint passFirst;     // first sample of this pass
uniform uint passCount;     // samples in this pass
#ifndef BOUND
const int MASK_WORDS = (DCS_TARGETS * 4 * DIGITS + 31) / 32;
#endif

// With the profile's atomic counters the depth test would run after the shader (its side
// effects forbid the driver's early test) and every rasterised fragment would be counted:
// the counters then measured 476 M fragments on the engine where 28.5 M reach the shader
// without them. Early tests keep the profiled run's fill the unprofiled one's.
#ifdef DCS_PROFILE
layout(early_fragment_tests) in;
#endif
flat in int gEdge;

#ifdef BOUND
layout(location = 0) out vec4 outBound;
#else
layout(location = 0) out vec4 outCounter0;
#if DCS_TARGETS > 1
layout(location = 1) out vec4 outCounter1;
#endif
#if DCS_TARGETS > 2
layout(location = 2) out vec4 outCounter2;
#endif
#if DCS_TARGETS > 3
layout(location = 3) out vec4 outCounter3;
#endif
#if DCS_TARGETS > 4
layout(location = 4) out vec4 outCounter4;
#endif
#if DCS_TARGETS > 5
layout(location = 5) out vec4 outCounter5;
#endif
#if DCS_TARGETS > 6
layout(location = 6) out vec4 outCounter6;
#endif
layout(location = DCS_TARGETS) out vec4 outChecksum;
#endif

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 gp = texelFetch(gPosition, px, 0);
  if (gp.w == 0.0) discard;
  PROFILE_COUNT(profFragments);
  // The point is moved off its surface towards the camera, where the reference's rays start
  // (shared.h): its own triangle then lies clearly on one side of every plane(p, e).
  vec3 p = penumbraShadowOrigin(gp.xyz, texelFetch(gNormal, px, 0).xyz, eyePosition);
  DcsEdge e = dcsEdges[gEdge];
  vec3 a = e.v0.xyz, b = e.v1.xyz;
  // n_e and the light centre's side of plane(p, e), bit for bit as the shadow-volume count
  // decides the point's side of the volume side through e (common_volume.glsl).
  vec3 ne;
  float dc = edgePlaneDistance(a, b, lightPosition, p, ne);
  float len = length(ne);
  if (len == 0.0) discard;
  if (abs(dc) > lightRadius * len) discard;  // the whole light on one side of plane(p, e)
  PROFILE_COUNT(profInPlane);
  float cSide = dc >= 0.0 ? 1.0 : -1.0;
  int m = dcsEdgeWeight(e, p);
  // sign(n_e . (s - p)) = -cSide for every covered sample; m_e(p) crossings of the mesh's
  // surface, each worth the mesh's units (1 unless semi-opaque occluders are coded, opacity.h).
  int delta = -int(cSide) * m * e.meta.w;
#ifdef BOUND
  if (delta <= 0) discard;
#else
  if (delta == 0) discard;
#endif
  if (lightCornerCount == 4) {
    vec3 corners[4] = vec3[4](lightCorners[0], lightCorners[1], lightCorners[2], lightCorners[3]);
    if (!dcsEdgeMeetsLightPyramid(p, a, b, lightPosition, corners)) discard;
  }
  PROFILE_COUNT(profWeighted);
  // The covered samples: the paper's 2D modes where the edge projects onto a planar light
  // (DCS_COVERAGE naive / lut, common_dcs.glsl), else the exact 3D test.
  bool exact = true;
#if DCS_COVERAGE != PENUMBRA_DCS_COVERAGE_EXACT
  vec2 q0, q1;
  int projected = dcsProjectEdge(p, a, b, lightPosition, q0, q1);
  if (projected == 0) discard;
  uvec4 field = uvec4(0u);
  if (projected > 0) {
    exact = false;
    field = dcsCoveredField(q0, q1, pixelSampleBase(px) / sampleCount, sampleCount);
  }
#endif
#ifdef BOUND
  bool hit = false;
#if DCS_COVERAGE != PENUMBRA_DCS_COVERAGE_EXACT
  hit = !exact && field != uvec4(0u);
#endif
  if (exact) {
    DcsCoverage cov = dcsCoverageSetup(p, a, b, lightPosition, ne, dc);
    uint first = pixelSampleBase(px);
    for (uint k = 0u; k < sampleCount && !hit; ++k) hit = dcsCovered(cov, samplePositions[first + k].xyz - lightPosition);
  }
  if (!hit) discard;
  outBound = vec4(float(delta), 0.0, 0.0, 0.0);
#else
  // The covered samples of the pass as a bit mask, then the packed values from it with
  // compile-time indices only (dynamic indexing of the outputs is slow on CPU drivers).
  uint base = pixelSampleBase(px) + passFirst;
  uint mask[MASK_WORDS];
  int covered = 0;
  if (exact) {
    DcsCoverage cov = dcsCoverageSetup(p, a, b, lightPosition, ne, dc);
    for (int w = 0; w < MASK_WORDS; ++w) {
      uint bits = 0u;
      for (uint k = 0u; k < 32u; ++k) {
        uint j = uint(w) * 32u + k;
        if (j >= passCount) break;
        if (dcsCovered(cov, samplePositions[base + j].xyz - lightPosition)) bits |= 1u << k;
      }
      mask[w] = bits;
    }
  }
#if DCS_COVERAGE != PENUMBRA_DCS_COVERAGE_EXACT
  else {
    for (int w = 0; w < MASK_WORDS; ++w) {
      uint j0 = uint(w) * 32u;
      uint left = passCount - min(passCount, j0);  // samples of the pass from j0 on
      uint bits = left > 0u ? dcsBitsFrom(field, passFirst + j0) : 0u;
      mask[w] = left < 32u ? bits & ((1u << left) - 1u) : bits;
    }
  }
#endif
  for (int w = 0; w < MASK_WORDS; ++w) covered += bitCount(mask[w]);
  if (covered == 0) discard;
  PROFILE_COUNT(profUpdating);
  vec4 acc[DCS_TARGETS];
  for (int t = 0; t < DCS_TARGETS; ++t) {
    for (int ch = 0; ch < 4; ++ch) {
      float value = 0.0, weight = float(delta);
      for (int d = 0; d < DIGITS; ++d, weight *= float(DCS_BASE)) {
        int j = (t * 4 + ch) * DIGITS + d;
        value += float((mask[j / 32] >> (j % 32)) & 1u) * weight;
      }
      acc[t][ch] = value;
    }
  }
  outCounter0 = acc[0];
#if DCS_TARGETS > 1
  outCounter1 = acc[1];
#endif
#if DCS_TARGETS > 2
  outCounter2 = acc[2];
#endif
#if DCS_TARGETS > 3
  outCounter3 = acc[3];
#endif
#if DCS_TARGETS > 4
  outCounter4 = acc[4];
#endif
#if DCS_TARGETS > 5
  outCounter5 = acc[5];
#endif
#if DCS_TARGETS > 6
  outCounter6 = acc[6];
#endif
  outChecksum = vec4(float(delta * covered), float(max(delta, 0)), 0.0, 0.0);
#endif
}
