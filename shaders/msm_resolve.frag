// msm and msm-soft shadow pass (src/techniques/msm): moment shadow mapping on the summed-area
// table of the four depth moments (vssm_sat.comp MOMENTS4), u = 2 x - 1 of vssm's normalised
// depth x.
//  * msm (Peters and Klein 2015): the box of filterTexels^2 texels around the receiver, the
//    Hamburger 4MSM shadow intensity (shared.h penumbraMsm4) of its moments.
//  * SOFT, msm-soft (Peters, Muenstermann, Wetzstein and Klein 2016, section 5): the blocker
//    search over pcss's search region, its average blocker depth from the same reconstruction
//    (the weight and depth of its points nearer than the receiver), the penumbra by parallel
//    planes (pcss_common.glsl penumbraRadius), then the 4MSM intensity over that kernel.
// Each box's moments are standardised (mean 0, variance 1) in the table's precision, then biased
// by momentBias (the paper's alpha, relative to the box's spread: shared.h penumbraMsmBias)
// before the float reconstruction. Divergence: the receiver depth of a box is the lowest depth
// of the receiver's plane over the box's corners (moment_kernel.glsl receiverAt), so that a
// tilted receiver does not shadow itself across a large kernel (the paper scales a depth bias
// with the kernel instead).
#include "single_view_bindings.h"
#include "pcss_common.glsl"
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
uniform float momentBias;
uniform int filterTexels;  // msm: the box's width
uniform int subKernels;    // msm-soft: the kernels' split, subKernels^2

out vec4 outVisibility;

REAL4 satAt(int x, int y) { return (x < 0 || y < 0) ? REAL4(0.0) : sat[y * mapSize + x]; }

// A box's moments, standardised in the table's precision and biased (shared.h penumbraMsmBias):
// b = (0, 1, skewness, kurtosis) and the mean and standard deviation of u. The table's rounding
// is an error of about n = unit roundoff x (hi.x + 1)(hi.y + 1) sqrt(hi.x + hi.y + 2) / area in
// each mean moment (corner sums of that many texels' |u^k| <= 1, summed along rows then
// columns), relative to the numbers it protects; below it the central moments are noise (a flat
// box has none, and its rounding would read as a random skewness): the variance is at least 3 n,
// the third and fourth central moments lose 10 n and 20 n of their size (soft thresholds).
#ifdef DOUBLE
#define SAT_EPSILON 1.1102230246251565e-16
#else
#define SAT_EPSILON 5.9604645e-08
#endif
struct Moments {
  vec4 b;
  float mean, sd;
};
Moments boxMoments(ivec2 lo, ivec2 hi) {
  REAL4 s = satAt(hi.x, hi.y) - satAt(lo.x - 1, hi.y) - satAt(hi.x, lo.y - 1) + satAt(lo.x - 1, lo.y - 1);
  REAL area = REAL((hi.x - lo.x + 1) * (hi.y - lo.y + 1));
  REAL4 m = s / area;
  REAL mu = m.x, mu2 = mu * mu;
  REAL n = REAL(SAT_EPSILON) * REAL(hi.x + 1) * REAL(hi.y + 1) * sqrt(REAL(hi.x + hi.y + 2)) / area;
  REAL c2 = max(m.y - mu2, REAL(3.0) * n);
  REAL c3 = m.z - 3.0 * mu * m.y + 2.0 * mu2 * mu;
  c3 = sign(c3) * max(abs(c3) - REAL(10.0) * n, REAL(0.0));
  REAL c4 = max(m.w - 4.0 * mu * m.z + 6.0 * mu2 * m.y - 3.0 * mu2 * mu2 - REAL(20.0) * n, c2 * c2);
  REAL sd = sqrt(c2);
  Moments r;
  r.b = penumbraMsmBias(float(c3 / (sd * c2)), float(c4 / (c2 * c2)), momentBias);
  r.mean = float(mu);
  r.sd = float(sd);
  return r;
}

// The 4MSM of a box for receiver depth uf (in u): (shadow intensity, the blockers' depth sum in u).
vec2 momentShadow(Moments m, float uf) {
  vec2 g = penumbraMsm4(m.b, (uf - m.mean) / m.sd);
  return vec2(g.x, m.mean * g.x + m.sd * g.y);
}

// The receiver's depth (u) for a box: its plane's lowest over the box's corners, not clamped to
// the depth range (the nearest occluder's own surface is at u = -1, and its biased depth below).
float receiverU(Receiver r, ivec2 lo, ivec2 hi) {
  float d = min(min(receiverDepthAt(r, vec2(lo)), receiverDepthAt(r, vec2(hi.x + 1, lo.y))),
                min(receiverDepthAt(r, vec2(lo.x, hi.y + 1)), receiverDepthAt(r, vec2(hi + 1))));
  return 2.0 * (d - depthMin) / (depthMax - depthMin) - 1.0;
}

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
      vec2 g = momentShadow(boxMoments(a, b), uf);
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
