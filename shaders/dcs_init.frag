// Initialises the packed counters of a pass with the integration constant D(c) in every digit
// (DCS section 7.3: "MUL r0.w, r0.w, 266305" for base 64), the checksum with passCount * D(c)
// and the pixel's bound with D(c).
// Every digit carries a bias (DCS_BIAS), so that a count that ends slightly negative (the
// shadow-volume count and the wedges disagree about a point on a volume's side: the edge band)
// is still decoded instead of borrowing from its neighbour.
layout(binding = PENUMBRA_UNIT_COUNTER) uniform sampler2D integrationConstant;
uniform float digitSum;  // sum of B^d over the digits of a channel
uniform uint passCount;

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
  float dc = round(texelFetch(integrationConstant, ivec2(gl_FragCoord.xy), 0).r) + float(DCS_BIAS);
  vec4 v = vec4(dc * digitSum);
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
  outChecksum = vec4(dc * float(passCount), dc, 0.0, 0.0);  // (digit sum, bound), dcs_wedge.frag
}
