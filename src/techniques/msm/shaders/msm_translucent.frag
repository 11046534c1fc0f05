// msm with translucent occluders (MSM-SOFT paper, "translucent occluders", as its JCGT extension
// (Peters et al. 2017) states it: shadows of translucent occluders "by simply rendering to a
// moment shadow map with alpha blending"): every fragment writes the four moments of its depth,
// u = 2 x - 1 of vssm's normalised depth x (vssm_sat.comp MOMENTS4), and a translucent one blends
// them over the texel's with its opacity (dual-source blending: dst = a b(u) + (1 - a) dst). The
// opaque surfaces are drawn first with depth writes and no blending; the translucent ones after,
// depth-tested against them and not writing depth. The texel then holds a mixture: a receiver
// behind every layer reads 1 - prod(1 - a) in front of it, the product dcs and the reference
// take; between layers the weights depend on the draw order (the paper's approximation).
#include "single_view_bindings.h"
#include "vssm_common.glsl"
#include "shading/shaders/alpha_test_depth.glsl"
uniform float mapNear;
uniform float opacity;  // 1: the opaque pass (blending off)
layout(location = 0, index = 0) out vec4 outMoments;
layout(location = 0, index = 1) out vec4 outWeight;
void main() {
  penumbraAlphaDiscard();
  float u = 2.0 * normalisedMapDepth(gl_FragCoord.z, mapNear) - 1.0;
  outMoments = vec4(u, u * u, u * u * u, u * u * u * u);
  outWeight = vec4(opacity);
}
