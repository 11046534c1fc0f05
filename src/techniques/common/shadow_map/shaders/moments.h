// The 4MSM reconstruction and its moment bias (msm, msm-soft, evsm's moment tables), the same in
// the shaders and the GL-free tests. Valid in C++ and GLSL (shared/shared.h); C++ includes it
// through techniques/common/shadow_map/moments.hpp.
#ifndef PENUMBRA_MOMENTS_H
#define PENUMBRA_MOMENTS_H

#include "shared/shared.h"

// ---- moment shadow maps (msm, msm-soft: src/techniques/msm) -------------------------------
// Peters and Klein 2015, "Moment shadow mapping", section 3.2 / Algorithm 2 (the Hamburger 4MSM):
// from the first four moments b = (E z, E z^2, E z^3, E z^4) of the depths in a filter region
// and a receiver depth zf, the distribution with the fewest points that matches b and has a
// point at zf (the bound's extremal one): its other points z2 < z3 are the roots of
// c1 + c2 z + c3 z^2, c = B^-1 (1, zf, zf^2), B the Hankel matrix [[1 b1 b2] [b1 b2 b3]
// [b2 b3 b4]] (solved by its LDL^T factorisation), and each point's weight is
// E[(Z - z_j)(Z - z_k)] / ((z_i - z_j)(z_i - z_k)) over the other two. Returns (G, D): G the
// weight of the points nearer than zf (the shadow intensity, 1 - visibility; the point at zf
// itself counts as lit, as the paper's), D their weighted depth sum (the moment soft shadows'
// blocker search, Peters, Muenstermann, Wetzstein and Klein 2016, section 5.1: the average
// blocker depth is D / G). b must be a moment vector with a positive definite B: the caller
// passes the moments of a standardised depth (mean 0, variance 1: B is then well conditioned in
// float), biased by penumbraMsmBias.
// The moment bias (Peters and Klein 2015, section 3.3: b' = (1 - alpha) b + alpha b*) on
// standardised moments (0, 1, skewness, kurtosis), towards those of the uniform distribution with
// the same mean and variance, (0, 1, 0, 9/5): B of a two-point distribution is singular (kurtosis
// = 1 + skewness^2); biased its last pivot is alpha (4/5 + skewness^2), relative to the moments'
// own spread, so the bias neither blurs a narrow cluster of depths (as a bias towards a fixed
// distribution over the whole depth range would) nor vanishes beside the float rounding of a
// skewed box's kurtosis. Divergence: the paper biases the raw moments towards a fixed vector.
PENUMBRA_FN vec4 penumbraMsmBias(float skewness, float kurtosis, float alpha) {
  return vec4(0.0f, 1.0f, (1.0f - alpha) * skewness, (1.0f - alpha) * kurtosis + alpha * 1.8f);
}

PENUMBRA_FN vec2 penumbraMsm4(vec4 b, float zf) {
  float d2 = b.y - b.x * b.x;                     // the LDL^T pivots of B
  float l32 = (b.z - b.x * b.y) / d2;
  float d3 = max(b.w - b.y * b.y - l32 * l32 * d2, 1e-20f);
  float y2 = zf - b.x, y3 = zf * zf - b.y - l32 * y2;
  float c3 = y3 / d3, c2 = y2 / d2 - l32 * c3;
  float c1 = 1.0f - b.x * c2 - b.y * c3;
  float mid = -0.5f * c2 / c3;
  float r = sqrt(max(mid * mid - c1 / c3, 0.0f));
  float z2 = mid - r, z3 = mid + r;
  // Weights of z2 and z3 (the one at zf is the rest).
  float w2 = (zf * z3 - b.x * (zf + z3) + b.y) / ((z2 - zf) * (z2 - z3));
  float w3 = (zf * z2 - b.x * (zf + z2) + b.y) / ((z3 - zf) * (z3 - z2));
  float g = 0.0f, depth = 0.0f;
  if (z2 < zf) {
    g += w2;
    depth += w2 * z2;
  }
  if (z3 < zf) {
    g += w3;
    depth += w3 * z3;
  }
  return vec2(clamp(g, 0.0f, 1.0f), depth);
}

#endif
