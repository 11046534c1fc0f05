// vssm and msm (src/techniques/vssm, msm): the summed-area table of the depth moments of the
// light centre's map, x the view depth normalised to [0, 1] over [depthMin, depthMax] (empty
// texels: 1).
//  * vssm (VSSM Algorithm 1, L3): (x, x^2). EXACT: x as a 15-bit integer and every sum in
//    doubles, which hold integers exactly below 2^53 (2048^2 texels of 32767^2 stay below): the
//    table is exact. Otherwise fp32 (the common implementation): at 1024^2-2048^2 the corner sums
//    swamp a box's variance (hard case 17).
//  * MOMENTS4 (msm): (u, u^2, u^3, u^4) of u = 2 x - 1 in [-1, 1], in doubles (DOUBLE: a sum's
//    rounding is 2^-53 of at most 2^22 texels, far below any moment bias) or fp32.
//    MOMENT_MAP: those moments read from a map instead of computed from the depth (msm's
//    translucent occluders, msm_translucent.frag).
//  * MOMENTS4 and EVSM (evsm, Lauritzen and McCool 2008): the two warps' moments (e+, e+^2, e-,
//    e-^2), e+ = exp(c+ u), e- = -exp(-c- u) (exponents evsmPositive, evsmNegative; the exp of
//    half the exponent in float, squared in the table's precision: c up to 176 in doubles).
// PASS 0: moments into the table; PASS 1: prefix sums along rows; PASS 2: along columns (a
// thread a row / column).
#include "single_view_bindings.h"
#if defined(MOMENTS4) && defined(DOUBLE)
#define SAT_T dvec4
#elif defined(MOMENTS4)
#define SAT_T vec4
#elif defined(EXACT)
#define SAT_T dvec2
#else
#define SAT_T vec2
#endif
#include "compute_index.glsl"
layout(local_size_x = PENUMBRA_MAP_LOCAL_SIZE) in;
layout(std430, binding = PENUMBRA_SSBO_VSSM_SAT) buffer Sat { SAT_T sat[]; };
layout(binding = PENUMBRA_UNIT_PCSS_DEPTH) uniform sampler2D depthRaw;
#ifdef MOMENT_MAP
// msm with translucent occluders: the moments come blended from a map (msm_translucent.frag).
layout(binding = PENUMBRA_UNIT_PCSS_AUX) uniform sampler2D momentMap;
#endif
uniform int satSize;
uniform int pass;
uniform float mapNear;
uniform float evsmPositive, evsmNegative;  // EVSM: the warps' exponents
#include "vssm_common.glsl"

void main() {
  int i = int(globalIndex());
  if (pass == 0) {
    if (i >= satSize * satSize) return;
#ifdef MOMENT_MAP
    sat[i] = SAT_T(texelFetch(momentMap, ivec2(i % satSize, i / satSize), 0));
#else
    float z = texelFetch(depthRaw, ivec2(i % satSize, i / satSize), 0).r;
    float x = normalisedMapDepth(z, mapNear);
#if defined(MOMENTS4) && defined(EVSM)
    float u = 2.0 * x - 1.0;
    SAT_T h = SAT_T(exp(0.5 * evsmPositive * u), 0.0, exp(-0.5 * evsmNegative * u), 0.0);
    h = SAT_T(h.x * h.x, 0.0, -h.z * h.z, 0.0);
    sat[i] = SAT_T(h.x, h.x * h.x, h.z, h.z * h.z);
#elif defined(MOMENTS4)
    SAT_T u = SAT_T(2.0 * x - 1.0);
    sat[i] = u * SAT_T(1.0, u.x, u.x * u.x, u.x * u.x * u.x);
#elif defined(EXACT)
    double q = double(round(x * PENUMBRA_VSSM_FIXED_ONE));
    sat[i] = dvec2(q, q * q);
#else
    sat[i] = vec2(x, x * x);
#endif
#endif
    return;
  }
  if (i >= satSize) return;
  SAT_T sum = SAT_T(0);
  for (int j = 0; j < satSize; ++j) {
    int k = pass == 1 ? i * satSize + j : j * satSize + i;
    sum += sat[k];
    sat[k] = sum;
  }
}
