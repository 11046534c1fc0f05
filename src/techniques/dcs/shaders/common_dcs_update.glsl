// The per-pixel update of one edge (DCS Algorithm 1 lines 3-8), shared by the raster path's
// wedge fragments (dcs_wedge.frag) and the compute path (dcs_wedge.comp): the sign and weight of
// the update at the visible point and the light samples it covers. Needs common_light.glsl,
// common_dcs.glsl and common_dcs_lut.glsl, and MASK_WORDS (32 samples a word) defined.
#include "techniques/dcs/shaders/dcs_modes.h"
#include "techniques/common/shadow_volume/shaders/volume_count.h"
#ifndef DCS_UPDATE_GLSL
#define DCS_UPDATE_GLSL

uniform float lightRadius;  // bounding radius of the light around its centre

// Edge e's update at the evaluation point p of pixel px for the pixel's samples
// [first, first + count) (count <= 32 * MASK_WORDS): returns delta, the change of each covered
// sample's count (0: none), and sets bit j of mask for sample first + j when e covers it.
int dcsEdgeUpdate(ivec2 px, vec3 p, int edgeId, uint first, uint count, out uint mask[MASK_WORDS]) {
  for (int w = 0; w < MASK_WORDS; ++w) mask[w] = 0u;
  DcsEdge e = dcsEdges[edgeId];
  vec3 a = e.v0.xyz, b = e.v1.xyz;
  // n_e and the light centre's side of plane(p, e), bit for bit as the shadow-volume count
  // decides the point's side of the volume side through e (volume_count.h).
  vec3 ne;
  float dc = penumbraEdgePlaneDistance(a, b, lightPosition, p, ne);
  float len = length(ne);
  if (len == 0.0) return 0;
  if (abs(dc) > lightRadius * len) return 0;  // the whole light on one side of plane(p, e)
  PROFILE_COUNT(profInPlane);
  float cSide = dc >= 0.0 ? 1.0 : -1.0;
  int m = dcsEdgeWeight(e, p);
  // sign(n_e . (s - p)) = -cSide for every covered sample; m_e(p) crossings of the mesh's
  // surface, each worth the mesh's units (1 unless semi-opaque occluders are coded, opacity.h).
  int delta = -int(cSide) * m * e.meta.w;
  if (delta == 0) return 0;
  if (lightCornerCount == 4) {
    vec3 corners[4] = vec3[4](lightCorners[0], lightCorners[1], lightCorners[2], lightCorners[3]);
    if (!dcsEdgeMeetsLightPyramid(p, a, b, lightPosition, corners)) return 0;
  }
  PROFILE_COUNT(profWeighted);
  // The covered samples: the paper's 2D modes where the edge projects onto a planar light
  // (DCS_COVERAGE naive / lut, common_dcs.glsl), else the exact 3D test.
  uint base = pixelSampleBase(px) + first;
#if DCS_COVERAGE != PENUMBRA_DCS_COVERAGE_EXACT
  vec2 q0, q1;
  int projected = dcsProjectEdge(p, a, b, lightPosition, q0, q1);
  if (projected == 0) return 0;
  if (projected > 0) {
    uvec4 field = dcsCoveredField(q0, q1, pixelSampleBase(px) / sampleCount, sampleCount);
    for (int w = 0; w < MASK_WORDS; ++w) {
      uint j0 = uint(w) * 32u;
      uint left = count - min(count, j0);  // samples from j0 on
      uint bits = left > 0u ? dcsBitsFrom(field, first + j0) : 0u;
      mask[w] = left < 32u ? bits & ((1u << left) - 1u) : bits;
    }
    return delta;
  }
#endif
  DcsCoverage cov = dcsCoverageSetup(p, a, b, lightPosition, ne, dc);
  for (int w = 0; w < MASK_WORDS; ++w) {
    uint bits = 0u;
    for (uint k = 0u; k < 32u; ++k) {
      uint j = uint(w) * 32u + k;
      if (j >= count) break;
      if (dcsCovered(cov, samplePositions[base + j].xyz - lightPosition)) bits |= 1u << k;
    }
    mask[w] = bits;
  }
  return delta;
}

// The index-weighted number of samples in mask: the sum of j + 1 over its set bits j (the
// weights of the second digit sum, dcs_resolve.frag), as bit counts of the index bits.
float dcsMaskIndexSum(uint mask[MASK_WORDS]) {
  float sum = 0.0;
  for (int w = 0; w < MASK_WORDS; ++w) {
    uint m = mask[w];
    int ones = bitCount(m);
    int positions = bitCount(m & 0xAAAAAAAAu) + 2 * bitCount(m & 0xCCCCCCCCu) + 4 * bitCount(m & 0xF0F0F0F0u) +
                    8 * bitCount(m & 0xFF00FF00u) + 16 * bitCount(m & 0xFFFF0000u);
    sum += float(positions + (w * 32 + 1) * ones);
  }
  return sum;
}

#endif
