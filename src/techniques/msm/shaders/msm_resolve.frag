// msm and msm-soft shadow pass (src/techniques/msm): moment shadow mapping on the summed-area
// table of the four depth moments (vssm_sat.comp MOMENTS4), u = 2 x - 1 of vssm's normalised
// depth x.
//  * msm (Peters and Klein 2015): the box of filterTexels^2 texels around the receiver, the
//    Hamburger 4MSM shadow intensity (common/shadow_map/shaders/moments.h penumbraMsm4) of its moments.
//  * SOFT, msm-soft (Peters, Muenstermann, Wetzstein and Klein 2016, section 5): the blocker
//    search over pcss's search region, its average blocker depth from the same reconstruction
//    (the weight and depth of its points nearer than the receiver), the penumbra by parallel
//    planes (pcss_common.glsl penumbraRadius), then the 4MSM intensity over that kernel.
// Each box's moments are standardised (mean 0, variance 1) in the table's precision, then biased
// by momentBias (the paper's alpha, relative to the box's spread: common/shadow_map/shaders/moments.h penumbraMsmBias)
// before the float reconstruction. Divergence: the receiver depth of a box is the lowest depth
// of the receiver's plane over the box's corners (moment_kernel.glsl receiverAt), so that a
// tilted receiver does not shadow itself across a large kernel (the paper scales a depth bias
// with the kernel instead).
#include "techniques/common/shadow_map/shaders/moments.h"
#include "single_view_bindings.h"
#include "pcss_common.glsl"
#include "moment_soft.glsl"
uniform float momentBias;

// A box's moments, standardised in the table's precision and biased (common/shadow_map/shaders/moments.h penumbraMsmBias):
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
  REAL4 s = boxSum(lo, hi);
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

// moment_soft.glsl's box: the 4MSM of its moments for receiver depth uf.
vec2 boxShadow(ivec2 a, ivec2 b, float uf) { return momentShadow(boxMoments(a, b), uf); }

