// Resolve of one pass: decode the packed counters (eq. 7-10), write each sample's visibility
// (above the horizon and count == 0: the Heaviside of eq. 5-6; with semi-opaque occluders the
// transmittance the count's units decode to, DCS_OPACITY and dcs/shaders/dcs_modes.h penumbraDcsTransmittance)
// into the per-sample array, and add this pass's share of the visibility buffer (eq. 1-2).
// A final count past its digit carries into its neighbour (-B at its digit, +1 at the next),
// one below zero borrows (+B, -1): either changes the digit sum, so comparing it with the
// checksum (the plain sum of all updates) detects it. Where the pixel's bound (D(c) + bias +
// its positive updates) fits the base, no count can pass its digit and a mismatch is an
// inconsistency (a borrow, reported: overflowPixels). Where it does not (dcs/packing.h: a plan
// for the final counts), a mismatch may be a carry (carryPixels: dcs.cpp renders again with a
// base above the bound); there a carry and a borrow of the same pixel cancel in the plain sum,
// so the sum weighted by sample index + 1 is compared as well (a carry out of sample j changes
// it by -(B - 1)(j + 1) + 1, a borrow by +(B - 1)(j + 1) - 1: one carry and one borrow never
// cancel in both).
#include "techniques/dcs/shaders/dcs_modes.h"
#include "dcs_bindings.h"
#include "common_light.glsl"
#include "common_dcs_pass.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
layout(binding = PENUMBRA_UNIT_DCS_COUNTERS) uniform sampler2DArray counters;
layout(binding = PENUMBRA_UNIT_DCS_CHECKSUM) uniform sampler2D checksum;
#ifdef PER_SAMPLE_OUT
layout(binding = PENUMBRA_IMAGE_SAMPLE_VIS, r32f) uniform writeonly image2DArray sampleVisibility;
#endif
layout(std430, binding = PENUMBRA_SSBO_DCS_STATUS) buffer DcsStatus {
  uint overflowPixels;   // digit sum != checksum: a counter left its digit (below -bias)
  uint maxCount;         // largest decoded count (with the bias)
  uint negativePixels;   // a count above the horizon ended in [-bias, -1] (dcs_init.frag): treated
                         // as 0, reported
  uint boundMax;         // largest D(c) + bias + positive updates (dcs_wedge.frag)
  uint firstNegative;    // the first pixel (y * width + x, rows from the top) with a negative count
  uint carryPixels;      // digit sums != checksums where a count may pass its digit: render again
};

uniform float counterBase;
uniform float opaqueUnits;  // dcs/opacity.h: units of an opaque surface (Q or U)
uniform float unitLog;      // product coding: -ln T of one unit

out vec4 outVisibility;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 p = texelFetch(gPosition, px, 0);
  if (p.w == 0.0) { outVisibility = vec4(0.0); return; }
  vec3 n = texelFetch(gNormal, px, 0).xyz;
  uint base = pixelSampleBase(px);
  vec3 v = vec3(0.0);
  float digitTotal = 0.0, digitWeighted = 0.0;
  bool bad = false;
  uint channels = (passCount + uint(DIGITS) - 1u) / uint(DIGITS);
  uint j = 0u;
  uint maxD = 0u;
  bool negative = false;
  for (uint ch = 0u; ch < channels; ++ch) {
    float value = texelFetch(counters, ivec3(px, int(ch / 4u)), 0)[ch % 4u];
    bad = bad || value < 0.0;
    for (int d = 0; d < DIGITS; ++d, ++j) {
      float q = floor(value / counterBase);
      float digit = value - q * counterBase;
      value = q;
      if (j >= passCount) continue;
      digitTotal += digit;
      digitWeighted += float(j + 1u) * digit;
      maxD = max(maxD, uint(digit));
      uint k = passFirst + j;
      vec3 x = samplePositions[base + k].xyz;
      bool above = aboveHorizon(p.xyz, n, x);
      negative = negative || (digit < float(DCS_BIAS) && above);
      float visible = above ? penumbraDcsTransmittance(digit - float(DCS_BIAS), DCS_OPACITY, opaqueUnits, unitLog) : 0.0;
#ifdef PER_SAMPLE_OUT
      imageStore(sampleVisibility, ivec3(px, int(k)), vec4(visible));
#endif
      v += sampleLuminance[base + k].rgb * visible;
    }
    // Every digit decoded (unused ones of the last channel hold D(c)): nothing may be left.
    bad = bad || value != 0.0;
  }
  vec3 sums = texelFetch(checksum, px, 0).rgb;
  // Clamped below 2^32 (uint() of a larger float is undefined): still past 2^24, still refused.
  atomicMax(boundMax, uint(min(sums.g, 4294967040.0)));
  bool mayCarry = sums.g > counterBase - 1.0;
  bad = bad || abs(digitTotal - sums.r) > 0.5 || (mayCarry && abs(digitWeighted - sums.b) > 0.5);
  if (bad && mayCarry) atomicAdd(carryPixels, 1u);
  else if (bad) atomicAdd(overflowPixels, 1u);
  if (negative) {
    atomicAdd(negativePixels, 1u);
    atomicMin(firstNegative, uint(px.y * textureSize(gPosition, 0).x + px.x));
  }
  if (!bad) atomicMax(maxCount, maxD);  // a wrapped digit is reported, not a count
  outVisibility = vec4(v / float(sampleCount), 1.0);
}
