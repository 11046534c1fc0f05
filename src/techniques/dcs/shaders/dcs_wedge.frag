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
// section 5.3; dcs.cpp checks it after the pass and plans the next frame from it), and the sum
// of the updates weighted by sample index + 1 (the second digit sum, dcs_resolve.frag).
#include "shared/numerics.h"
#include "common_light.glsl"
#include "common_dcs.glsl"
#include "common_dcs_pass.glsl"
#include "common_dcs_lut.glsl"
const int MASK_WORDS = (DCS_TARGETS * 4 * DIGITS + 31) / 32;
#include "common_dcs_update.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
uniform vec3 eyePosition;

// With the profile's atomic counters the depth test would run after the shader (its side
// effects forbid the driver's early test) and every rasterised fragment would be counted:
// the counters then measured 476 M fragments on the engine where 28.5 M reach the shader
// without them. Early tests keep the profiled run's fill the unprofiled one's.
#ifdef DCS_PROFILE
layout(early_fragment_tests) in;
#endif
flat in int gEdge;
flat in int gFacing;  // dcs_wedge.geom: the facing of an unfolded face, 0: none

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
  // A fragment of a folded sliver (dcs_wedge.geom) counts with the opposite sign: the signed
  // coverage of a wedge's front faces is 1 at every pixel inside its outline.
  int coverage = gFacing == 0 || gl_FrontFacing == (gFacing > 0) ? 1 : -1;
#ifdef DCS_PROFILE
  dcsProfileStep = uint(coverage);
#endif
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 gp = texelFetch(gPosition, px, 0);
  if (gp.w == 0.0) discard;
  PROFILE_COUNT(profFragments);
  // The point is moved off its surface towards the camera, where the reference's rays start
  // (volume_count.h): its own triangle then lies clearly on one side of every plane(p, e).
  vec3 p = penumbraShadowOrigin(gp.xyz, texelFetch(gNormal, px, 0).xyz, eyePosition);
  uint mask[MASK_WORDS];
  int delta = coverage * dcsEdgeUpdate(px, p, gEdge, passFirst, passCount, mask);
  int covered = 0;
  for (int w = 0; w < MASK_WORDS; ++w) covered += bitCount(mask[w]);
  if (delta == 0 || covered == 0) discard;
  PROFILE_COUNT(profUpdating);
  // The packed values from the mask with compile-time indices only (dynamic indexing of the
  // outputs is slow on CPU drivers).
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
  outChecksum = vec4(float(delta * covered), float(max(delta, 0)), float(delta) * dcsMaskIndexSum(mask), 0.0);
}
