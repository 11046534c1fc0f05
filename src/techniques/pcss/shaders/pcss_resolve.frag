// pcss shadow pass (src/techniques/pcss): percentage-closer soft shadows (Fernando 2005) with
// Sterna's (2018) sampling (pcss_common.glsl). The penumbra radius comes from
//  * (default) the blocker search right here (Sterna 2.1, "regular CHSS"),
//  * PENUMBRA_MASK: the quarter-resolution, blurred penumbra mask (Sterna 2.2),
//  * MIN_FILTER: the blurred min-filtered map as the blocker depth (Sterna 2.3),
//  * FIXED: the blocker-search radius itself, no search (Sterna's non-contact-hardening
//    "regular shadow mask", for timing),
//  * DENSE: Fernando's original, every texel of the search and filter kernels (at most 32 x 32),
//    the PCSS the VSSM paper compares with.
// CHECKERBOARD (Sterna 3): this pass covers every other pixel (a half-width target); the
// upsample pass (pcss_checker.frag) fills in the rest.
#include "single_view_bindings.h"
#include "pcss_common.glsl"
#if defined(PENUMBRA_MASK) || defined(MIN_FILTER)
layout(binding = PENUMBRA_UNIT_PCSS_AUX) uniform sampler2D pcssAux;  // linear, clamp
#endif
uniform vec2 screenSize;

out vec4 outVisibility;

float shadowFactor(ivec2 px, Receiver r) {
#ifdef CHECKERBOARD
  float phi = TWO_PI * interleavedGradientNoise((vec2(px) + 0.5) * vec2(1.0, 4.0));
#else
  float phi = TWO_PI * interleavedGradientNoise(vec2(px) + 0.5);
#endif
#if defined(PENUMBRA_MASK)
  float radius = texture(pcssAux, (vec2(px) + 0.5) / screenSize).r;
  if (radius <= 0.0) return percentageCloser(r, 0.5 / float(mapSize), phi);
#elif defined(MIN_FILTER)
  float z = texture(pcssAux, r.uv).r;  // the nearest depth around, blurred
  if (!(z > r.z)) return 1.0;
  float radius = penumbraRadius(r, mapNear / z);
#elif defined(FIXED)
  float radius = searchRadius(r);
#elif defined(DENSE)
  float blocker = averageBlockerDepthDense(r);
  if (blocker < 0.0) return 1.0;
  return percentageCloserDense(r, penumbraRadius(r, blocker));
#else
  float blocker = averageBlockerDepth(r, phi);
  if (blocker < 0.0) return 1.0;
  float radius = penumbraRadius(r, blocker);
#endif
#ifndef DENSE
  return percentageCloser(r, radius, phi);
#endif
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
#ifdef CHECKERBOARD
  px.x = 2 * px.x + (px.y & 1);
  if (px.x >= int(screenSize.x)) { outVisibility = vec4(0.0); return; }
#endif
  vec3 p, n;
  if (texelFetch(gPosition, px, 0).w == 0.0) { outVisibility = vec4(0.0); return; }
  Receiver r = receiverOf(px, p, n);
  vec3 luminance = horizonLuminance(px, p, n);
  float s = (luminance == vec3(0.0) || !r.inView) ? 1.0 : shadowFactor(px, r);
  outVisibility = vec4(luminance * s, 1.0);
}
