// Initialises the packed counters of a pass with the integration constant D(c) in every digit
// (DCS section 7.3: "MUL r0.w, r0.w, 266305" for base 64), the checksum with passCount * D(c),
// the pixel's bound with D(c) and the index-weighted checksum with D(c) (1 + ... + passCount).
// Path crossings (hard case 28, a light partly inside a closed occluder or through one): where
// the straight path from c to sample s passes through a triangle t, the count changes without
// any edge being crossed: the segment x -> p gains or loses t as its end x passes t's plane.
// Before the crossing t is crossed exactly when p lies on s's side of t, after it when p lies
// on c's side, so D(s) gets w_t(p) ([p on c's side] - [p on s's side]), with w_t the weight t has
// in the count (common_dcs.glsl dcsEdgeWeight: 1, or for the closed rule [p behind t]); a path
// end on t (side 0) counts neither (silhouette.h: a light point on a surface is not occluded by
// it). ShadowVolumeCounter::place lists them per sample on the CPU, in double; this pass adds
// them per sample digit.
#include "shared/numerics.h"
#include "dcs_bindings.h"
#include "common_light.glsl"
#include "common_dcs_pass.glsl"
// Every digit carries a bias (DCS_BIAS), so that a count that ends slightly negative (the
// shadow-volume count and the wedges disagree about a point on a volume's side: the edge band)
// is still decoded instead of borrowing from its neighbour.
layout(binding = PENUMBRA_UNIT_COUNTER) uniform sampler2D integrationConstant;
uniform float digitSum;  // sum of B^d over the digits of a channel
uniform int pathCrossings;  // 1: the light has path crossings (PENUMBRA_SSBO_DCS_PATH)
uniform vec3 eyePosition;
layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;

struct DcsPathCrossing {
  vec4 plane;  // the triangle's plane (n, d), as dcsIncidences store it
  ivec4 meta;  // x c's side, y s's side (+-1, 0 on the plane), z 1 for the closed rule, w units
};
layout(std430, binding = PENUMBRA_SSBO_DCS_PATH_FIRST) readonly buffer DcsPathFirst { uint dcsPathFirst[]; };
layout(std430, binding = PENUMBRA_SSBO_DCS_PATH) readonly buffer DcsPath { DcsPathCrossing dcsPath[]; };

// What the path crossings of sample k (global index) add to its count at p.
float pathGain(uint k, vec3 p) {
  int gain = 0;
  for (uint i = dcsPathFirst[k]; i < dcsPathFirst[k + 1u]; ++i) {
    DcsPathCrossing x = dcsPath[i];
    precise float f = dot(x.plane.xyz, p) + x.plane.w;
    int side = f > 0.0 ? 1 : (f < 0.0 ? -1 : 0);
    int before = int(x.meta.x != 0 && side == -x.meta.x);  // p opposite c: t crossed before
    int after = int(x.meta.y != 0 && side == -x.meta.y);   // p opposite s: t crossed after
    int w = x.meta.z != 0 ? int(f < 0.0) : 1;
    gain += x.meta.w * w * (after - before);
  }
  return float(gain);
}

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

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  float dc = round(texelFetch(integrationConstant, px, 0).r) + float(DCS_BIAS);
  vec4 v = vec4(dc * digitSum);
  vec4 gp = texelFetch(gPosition, px, 0);
  if (pathCrossings != 0 && gp.w != 0.0) {
    // Per sample digit: D(c) plus its path crossings; the checksum gets their sum and the bound
    // the largest gain.
    vec3 p = penumbraShadowOrigin(gp.xyz, texelFetch(gNormal, px, 0).xyz, eyePosition);
    uint base = pixelSampleBase(px) + passFirst;
    vec4 acc[DCS_TARGETS];
    float total = 0.0, weighted = 0.0, most = 0.0;
    for (int t = 0; t < DCS_TARGETS; ++t) {
      for (int ch = 0; ch < 4; ++ch) {
        float value = 0.0, weight = 1.0;
        for (int d = 0; d < DIGITS; ++d, weight *= float(DCS_BASE)) {
          uint j = uint((t * 4 + ch) * DIGITS + d);
          float count = dc;
          if (j < passCount) {
            float g = pathGain(base + j, p);
            count += g;
            total += count;
            weighted += float(j + 1u) * count;
            most = max(most, g);
          }
          value += count * weight;
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
    outChecksum = vec4(total, dc + most, weighted, 0.0);
    return;
  }
  outCounter0 = v;
#if DCS_TARGETS > 1
  outCounter1 = v;
#endif
#if DCS_TARGETS > 2
  outCounter2 = v;
#endif
#if DCS_TARGETS > 3
  outCounter3 = v;
#endif
#if DCS_TARGETS > 4
  outCounter4 = v;
#endif
#if DCS_TARGETS > 5
  outCounter5 = v;
#endif
#if DCS_TARGETS > 6
  outCounter6 = v;
#endif
  // (digit sum, bound, index-weighted digit sum), dcs_wedge.frag
  outChecksum = vec4(dc * float(passCount), dc, dc * float(passCount * (passCount + 1u) / 2u), 0.0);
}
