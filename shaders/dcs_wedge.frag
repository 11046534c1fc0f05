// Depth-complexity update of one edge at one pixel (DCS Algorithm 1), for the samples of this
// pass, into float-base packed counters (eq. 7-10): sample j of the pass is digit j % DIGITS of
// channel (j / DIGITS) % 4 of target j / (4 * DIGITS); adding delta * base^digit updates it.
// Each fragment's contribution has one sign for all its samples; passSign selects the positive
// (outer) or negative (inner) contributions, so outer edges are added before inner ones and no
// digit is ever below its final value during the update.
// BOUND: instead, add m for every positive contribution that covers any sample of the pixel
// into one R32F target: an upper bound of how far any counter of the pixel rises above D(c)
// (adaptive sampling, section 5.3).
#include "common_light.glsl"
#include "common_dcs.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
uniform float surfaceOffset;  // Scene::surfaceOffset(), as the reference's ray origins
uniform float lightRadius;  // bounding radius of the light around its centre
uniform int passSign;       // +1 or -1
uniform uint passFirst;     // first sample of this pass
uniform uint passCount;     // samples in this pass
uniform float digitWeights[8];  // B^0 .. B^7 (exact powers of two)

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
  // The point is moved off its surface to the camera side, as the reference's ray origin is:
  // its own triangle then lies clearly on one side of every plane(p, e).
  vec3 p = gp.xyz + texelFetch(gNormal, px, 0).xyz * surfaceOffset;
  DcsEdge e = dcsEdges[gEdge];
  vec3 a = e.v0.xyz, b = e.v1.xyz;
  vec3 ne = cross(a - p, b - a);  // == cross(a - p, b - p), see common_dcs.glsl
  float len = length(ne);
  if (len == 0.0) discard;
  float dc = dot(ne, lightPosition - p);
  if (abs(dc) > lightRadius * len) discard;  // the whole light on one side of plane(p, e)
  float cSide = dc >= 0.0 ? 1.0 : -1.0;
  int m = dcsEdgeWeight(e, p, ne);
  int delta = -int(cSide) * m;  // sign(n_e . (s - p)) = -cSide for every covered sample
  if (delta == 0 || (delta > 0) != (passSign > 0)) discard;
#ifdef BOUND
  uint first = pixelSampleBase(px);
  for (uint k = 0u; k < sampleCount; ++k) {
    if (dcsCovered(p, a, b, lightPosition, samplePositions[first + k].xyz)) {
      outBound = vec4(float(delta), 0.0, 0.0, 0.0);
      return;
    }
  }
  discard;
#else
  vec4 acc[DCS_TARGETS];
  for (int t = 0; t < DCS_TARGETS; ++t) acc[t] = vec4(0.0);
  uint base = pixelSampleBase(px) + passFirst;
  int covered = 0;
  for (uint j = 0u; j < passCount; ++j) {
    if (!dcsCovered(p, a, b, lightPosition, samplePositions[base + j].xyz)) continue;
    uint digit = j % uint(DIGITS);
    uint channel = (j / uint(DIGITS)) % 4u;
    uint target = j / uint(4 * DIGITS);
    acc[target][channel] += float(delta) * digitWeights[digit];
    ++covered;
  }
  if (covered == 0) discard;
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
  outChecksum = vec4(float(delta * covered), 0.0, 0.0, 0.0);
#endif
}
