// The alpha test of the occluder passes (depth maps, transmittance maps, vwss's points): the
// texture coordinate from the vertex stage (mvr_depth.vert, vwss_points.vert) or, with LAYERED,
// from mvr_depth.geom; call penumbraAlphaDiscard() first in main().
#include "shading/shaders/alpha_test.glsl"
#ifdef LAYERED
in vec2 gUv;
#define PENUMBRA_OCCLUDER_UV gUv
#else
in vec2 vUv;
#define PENUMBRA_OCCLUDER_UV vUv
#endif
layout(binding = PENUMBRA_UNIT_MATERIAL_TEX) uniform sampler2D occluderTexture;

void penumbraAlphaDiscard() {
  if (!penumbraSurfacePresent(occluderTexture, PENUMBRA_OCCLUDER_UV)) discard;
}
