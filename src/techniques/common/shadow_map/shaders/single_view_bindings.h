// Binding points of the single-view shadow-map techniques (src/techniques/shadow_map/
// single_view.h: pcss, vssm), valid in C++ and GLSL. Shared ones are in shared/shared.h (see
// dcs_bindings.h).
#ifndef PENUMBRA_SINGLE_VIEW_BINDINGS_H
#define PENUMBRA_SINGLE_VIEW_BINDINGS_H

#define PENUMBRA_UNIT_PCSS_DEPTH 16     // pcss: the light centre's depth map, read raw (blocker search)
#define PENUMBRA_UNIT_PCSS_COMPARE 17   // pcss: the same map through a depth-comparison sampler (PCF)
#define PENUMBRA_UNIT_PCSS_AUX 18       // pcss: the penumbra mask or the min-filtered map, read by the shadow pass
#define PENUMBRA_UNIT_PCSS_SOURCE 19    // pcss: input of a separable filter / the checkerboard target
#define PENUMBRA_SSBO_VSSM_SAT 9        // vssm: summed-area table of the depth moments, a texel a pair
#define PENUMBRA_SSBO_VSSM_HSM 10       // vssm: min-max hierarchical shadow map, all levels, a texel a pair
#define PENUMBRA_VSSM_FIXED_ONE 32767.0 // vssm exact SAT: depth in [0,1] as 15-bit integers (sums of
                                        // squares stay below 2^53 at 2048^2: exact in doubles)

#endif
