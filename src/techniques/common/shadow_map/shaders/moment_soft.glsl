// The four-moment summed-area-table techniques' kernels and shadow pass (msm, msm-soft, evsm:
// src/techniques/msm, evsm), after pcss_common.glsl. The including shader defines
//   vec2 boxShadow(ivec2 a, ivec2 b, float uf): over the texel box [a, b] for the receiver depth
//   uf (u = 2 x - 1 of vssm's normalised depth x, unclamped), the shadow intensity and the
//   blockers' depth sum (their mean depth times their share),
// after this file's declarations (satAt, receiverU); this file's main() runs the kernels:
// SOFT, the PCSS framework (the blocker search over pcss's region, the penumbra by parallel
// planes); else a filterTexels-wide box around the receiver (hard shadows from the light centre).
#ifdef DOUBLE
#define REAL double
#define REAL4 dvec4
#else
#define REAL float
#define REAL4 vec4
#endif
layout(std430, binding = PENUMBRA_SSBO_VSSM_SAT) readonly buffer Sat { REAL4 sat[]; };
#include "vssm_common.glsl"
#include "moment_kernel.glsl"
uniform int filterTexels;  // hard: the box's width
uniform int subKernels;    // SOFT: the kernels' split, subKernels^2

out vec4 outVisibility;

REAL4 satAt(int x, int y) { return (x < 0 || y < 0) ? REAL4(0.0) : sat[y * mapSize + x]; }

// The box [lo, hi]'s sums.
REAL4 boxSum(ivec2 lo, ivec2 hi) {
  return satAt(hi.x, hi.y) - satAt(lo.x - 1, hi.y) - satAt(hi.x, lo.y - 1) + satAt(lo.x - 1, lo.y - 1);
}

// The receiver's depth (u) for a box: its plane's lowest over the box's corners, not clamped to
// the depth range (the nearest occluder's own surface is at u = -1, and its biased depth below).
float receiverU(Receiver r, ivec2 lo, ivec2 hi) {
  float d = min(min(receiverDepthAt(r, vec2(lo)), receiverDepthAt(r, vec2(hi.x + 1, lo.y))),
                min(receiverDepthAt(r, vec2(lo.x, hi.y + 1)), receiverDepthAt(r, vec2(hi + 1))));
  return 2.0 * (d - depthMin) / (depthMax - depthMin) - 1.0;
}

vec2 boxShadow(ivec2 a, ivec2 b, float uf);

// Over the kernel [lo, hi] split into div x div sub-kernels, each with its own receiver depth
// (the split vssm uses against non-planar receivers, VSSM section 5.2): (shadow intensity, the
// blockers' mean depth in u, or the receiver's where there are none).
vec2 kernelShadow(Receiver r, ivec2 lo, ivec2 hi, int div) {
  float area = 0.0, shadow = 0.0, depth = 0.0, receiver = 0.0;
  for (int j = 0; j < div; ++j)
    for (int i = 0; i < div; ++i) {
      ivec2 a, b;
      if (!cellBox(lo, hi, div, ivec2(i, j), a, b)) continue;
      float w = float((b.x - a.x + 1) * (b.y - a.y + 1));
      float uf = receiverU(r, a, b);
      vec2 g = boxShadow(a, b, uf);
      area += w;
      shadow += w * g.x;
      depth += w * g.y;
      receiver += w * uf;
    }
  // The blockers' mean depth, drawn towards the receiver where the search finds almost none
  // (the paper's fully-lit bias, 1e-3 of the kernel): the kernel then shrinks to the texel.
  float fullyLit = 1e-3 * area;
  return vec2(shadow / area, (depth + fullyLit * receiver / area) / (shadow + fullyLit));
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec3 p, n;
  if (texelFetch(gPosition, px, 0).w == 0.0) { outVisibility = vec4(0.0); return; }
  Receiver r = receiverOf(px, p, n);
  vec3 luminance = horizonLuminance(px, p, n);
  float s = 1.0;
  if (luminance != vec3(0.0) && r.inView) {
    ivec2 lo, hi;
#ifdef SOFT
    kernelBox(r, searchRadius(r), lo, hi);
    float ub = kernelShadow(r, lo, hi, subKernels).y;
    float blocker = viewDepth(clamp(0.5 * ub + 0.5, 0.0, 1.0));
    kernelBox(r, penumbraRadius(r, max(blocker, mapNear)), lo, hi);
    s = 1.0 - kernelShadow(r, lo, hi, subKernels).x;
#else
    ivec2 c = clamp(ivec2(floor(r.uv * float(mapSize))), ivec2(0), ivec2(mapSize - 1));
    lo = clamp(c - ivec2(filterTexels / 2), ivec2(0), ivec2(mapSize - 1));
    hi = clamp(c + ivec2(filterTexels / 2), ivec2(0), ivec2(mapSize - 1));
    s = 1.0 - kernelShadow(r, lo, hi, 1).x;
#endif
  }
  outVisibility = vec4(luminance * s, 1.0);
}
