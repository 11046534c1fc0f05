// `msm` and `msm-soft`: moment shadow mapping (Peters and Klein, I3D 2015, "Moment shadow
// mapping": four moments of the depth a texel, the Hamburger 4MSM reconstruction with its moment
// bias) as a filtered hard-shadow baseline from the light centre, and moment soft shadows
// (Peters, Muenstermann, Wetzstein and Klein 2016, "Beyond hard shadows: moment shadow maps for
// single scattering, soft shadows and translucent occluders", section 5: the PCSS framework with
// the blocker search and the filtering both from the moments, through summed-area tables). On
// the single-view framework and summed-area machinery vssm uses (src/techniques/common/shadow_map/shaders/vssm_sat.comp
// MOMENTS4, msm_resolve.frag; the reconstruction is common/shadow_map/shaders/moments.h penumbraMsm4).
//
// Divergences, each measured in tests/render_msm_test.cpp: the table holds the moments
// themselves in doubles (sat-bits 64, default) or fp32 (32), not the paper's 16-bit optimised
// quantisation (which a table of sums cannot keep); each box's moments are standardised in the
// table's precision before the float reconstruction, and the moment bias acts on the
// standardised moments (towards the uniform distribution of the box's own mean and variance,
// common/shadow_map/shaders/moments.h penumbraMsmBias), so that it neither blurs small depth differences nor depends on
// the depth range; the receiver depth of a box is its plane's lowest over the box (moment_kernel.glsl).
#pragma once

#include <memory>

#include "pipeline/technique.h"

namespace penumbra {

struct MsmOptions {
  bool soft = false;         // msm-soft: blocker search and penumbra kernel; msm: a fixed box
  int filter = 3;            // msm: the box's width in texels (odd)
  int subKernels = 4;        // msm-soft: each kernel split into subKernels^2 (own receiver depths)
  double momentBias = 1e-5;  // alpha on the standardised moments (common/shadow_map/shaders/moments.h penumbraMsmBias)
  int satBits = 64;          // 64: the table in doubles; 32: fp32
  bool translucent = false;  // semi-opaque occluders blend their moments (msm_translucent.frag)
};

// The parameters of a preset, its values their defaults: the map ones, filter (msm only),
// sub-kernels (msm-soft only), moment-bias, sat-bits, translucent.
std::vector<ParamSpec> msmParams(const MsmOptions& preset);
std::unique_ptr<Technique> makeMomentShadowMapping(const TechniqueArgs& args, MsmOptions preset);

}  // namespace penumbra
