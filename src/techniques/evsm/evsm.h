// `evsm`: exponential variance shadow maps (Lauritzen and McCool 2008, "Layered variance shadow
// maps", section 4's exponential warp in its two-exponent, four-moment form: e+ = exp(c+ u),
// e- = -exp(-c- u) of the depth u in [-1, 1], the lit share the smaller of the two warps'
// Chebyshev bounds) with the PCSS framework and summed-area penumbra of vssm: the engines' fix for
// variance maps' light bleeding under area lights (Unity HDRP's area-light shadows, Filament's VSM
// option). On the single-view framework and the four-moment tables of msm
// (src/techniques/common/shadow_map/shaders/vssm_sat.comp EVSM, evsm_resolve.frag, moment_soft.glsl).
//
// The exponents and their overflow limits: a table of N texels holds sums of e+^2 up to
// N exp(2 c+), so c+ and c- are at most (ln(max) - ln N) / 2: in doubles (sat-bits 64, default)
// 175.7 (the warp is the float exp of half the exponent, squared in double), in fp32 (ln(FLT_MAX)
// - ln N) / 2 = 37.1 at 1024^2 maps, 36.3 at 2048^2 (each with a 1% margin). A larger exponent is clamped to the limit
// with a warning naming the technique, the table and the limit (never NaN); the statistics give the exponents used.
#pragma once

#include <memory>

#include "pipeline/technique.h"

namespace penumbra {

struct EvsmOptions {
  double positive = 40.0;  // c+ (defaults measured: tests/render_msm_test.cpp Evsm.*)
  double negative = 10.0;  // c-
  int subKernels = 4;      // each kernel split into subKernels^2 with their own receiver depths
  int satBits = 64;        // 64: the table in doubles; 32: fp32
};

// The largest exponent a table of `texels` texels at `satBits` holds (see above).
double evsmExponentLimit(int satBits, double texels);

// The parameters: the map ones, positive-exponent, negative-exponent, sub-kernels, sat-bits.
std::vector<ParamSpec> evsmParams(const EvsmOptions& preset);
std::unique_ptr<Technique> makeExponentialVarianceShadowMaps(const TechniqueArgs& args, EvsmOptions preset);

}  // namespace penumbra
