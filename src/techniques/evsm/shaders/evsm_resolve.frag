// evsm shadow pass (src/techniques/evsm): exponential variance shadow maps (Lauritzen and McCool
// 2008, "Layered variance shadow maps", the exponential warp; the two-exponent, four-moment
// variant) in the PCSS framework on summed-area tables, as vssm (moment_soft.glsl SOFT): each
// sub-kernel's lit share is the smaller of Chebyshev's bounds (VSSM eq. 1) on the two warped
// depths, e+ = exp(c+ u) and e- = -exp(-c- u) (vssm_sat.comp EVSM); the blocker search's average
// depth is VSSM's eq. 4 in the negative warp, (E[e-] - P- e-(t)) / (1 - P-), unwarped.
// Computed in the table's precision (REAL): the warped moments exceed float's range in doubles.
#include "single_view_bindings.h"
#include "pcss_common.glsl"
#include "moment_soft.glsl"
uniform float evsmPositive, evsmNegative;  // the exponents (the technique clamps them to the table's range)

#ifdef DOUBLE
#define SAT_EPSILON 1.1102230246251565e-16
#else
#define SAT_EPSILON 5.9604645e-08
#endif

// Chebyshev's one-tailed bound on the lit share for the warped receiver depth t from a box's
// mean m1 and mean square m2 of the warped depth; the variance at least `floorVar`.
REAL litBound(REAL m1, REAL m2, REAL t, REAL floorVar) {
  if (t <= m1) return REAL(1.0);
  REAL var = max(m2 - m1 * m1, floorVar);
  REAL d = t - m1;
  return var / (var + d * d);
}

vec2 boxShadow(ivec2 a, ivec2 b, float uf) {
  REAL area = REAL((b.x - a.x + 1) * (b.y - a.y + 1));
  // The box's corner sums, once: its means, and the table's rounding in each mean square
  // (relative to the corner sums it protects; a flat box has no variance and its rounding would
  // read as one).
  REAL4 c0 = satAt(b.x, b.y), c1 = satAt(a.x - 1, b.y), c2 = satAt(b.x, a.y - 1), c3 = satAt(a.x - 1, a.y - 1);
  REAL4 m = (c0 - c1 - c2 + c3) / area;
  REAL path = sqrt(REAL(b.x + b.y + 2)) * REAL(SAT_EPSILON) / area;
  REAL floorPos = path * (abs(c0.y) + abs(c1.y) + abs(c2.y) + abs(c3.y));
  REAL floorNeg = path * (abs(c0.w) + abs(c1.w) + abs(c2.w) + abs(c3.w));
  REAL hp = REAL(exp(0.5 * evsmPositive * uf));
  REAL tp = hp * hp;
  REAL hn = REAL(exp(-0.5 * evsmNegative * uf));
  REAL tn = -hn * hn;
  REAL litNeg = litBound(m.z, m.w, tn, floorNeg);
  REAL lit = min(litBound(m.x, m.y, tp, floorPos), litNeg);
  float g = float(REAL(1.0) - lit);
  if (!(g > 0.0) || !(litNeg < REAL(1.0))) return vec2(g, g * uf);
  // Eq. 4 in the negative warp: the blockers' mean warped depth relative to the receiver's (above
  // 1: in front of it), unwarped. Not the positive warp's: it magnifies the receiver's own depths
  // behind t (z_unocc = t) exponentially, and its estimate lands on the receiver.
  float ratio = float(max((m.z - litNeg * tn) / ((REAL(1.0) - litNeg) * tn), REAL(1.0)));
  float ub = uf - log(ratio) / evsmNegative;
  return vec2(g, g * max(ub, -1.0));
}
