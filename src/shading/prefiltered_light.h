// The prefiltered emission of a textured rect or disk light, for the unshadowed term of the ratio
// estimator (Heitz, Dupuy, Hill and Neubelt 2016, "Real-time polygonal-light shading with linearly
// transformed cosines", section 5.3; the lookup is shading/shaders/shading.h penumbraPrefilterFootprint). No GL.
//
// Level k is the emission convolved with an isotropic Gaussian of sigma_k = sigma_0 2^k (light uv
// units; sigma_0 one texel) and normalised by the Gaussian's weight on the light:
//   L_k(x) = integral G_k(x - y) L(y) chi(y) dy / integral G_k(x - y) chi(y) dy,
// chi the light's support in uv (the unit square; a disk's inscribed disk), so that a lookup near
// or beyond the light's border averages only what the light emits there (the paper extends the
// texture into a margin; this is that margin made exact for a Gaussian weight). Where a level's
// weight is too small (far outside the light at a small sigma) it blends into the next coarser
// level. A lookup mixes the levels (shading/shaders/shading.h penumbraPrefilterWeight). The chain covers uv in [-m, 1 +
// m]^2, m = PENUMBRA_PREFILTER_MARGIN; the coarsest level has sigma >= 2 (the whole light's average, nearly, anywhere
// in the margin).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"

namespace penumbra::shading {

struct PrefilteredLight {
  int size = 0;         // texels a side of every level
  float sigma0 = 0.0f;  // level 0's sigma in light uv (level k: sigma0 2^k)
  int levels = 0;
  std::vector<glm::vec4> texels;  // [level][row (v)][column (u)]: rgb, and the level's weight on the light
  bool empty() const { return texels.empty(); }
};

// The chain of an emission texture (linear RGB, as the light's samples read it through
// emissionAt): texel density that of the texture's larger side, clamped to 32..128 texels per
// light uv unit; 4 x 4 points a texel sample the light. disk: the support is the disk inscribed
// in the uv square.
PrefilteredLight prefilterLight(const Image& emission, bool disk);

// Level k at light uv as the GPU reads it (shaders/pipeline_shade.frag): bilinear at
// penumbraPrefilterCoordinates(uv) through texel centres, clamped to the edge.
glm::vec4 prefilteredLevel(const PrefilteredLight& chain, glm::vec2 uv, int k);

// L_D at a footprint (u, v, d) of shading/shaders/shading.h penumbraPrefilterFootprint, as the GPU computes it: the
// levels mixed with penumbraPrefilterWeight(d) as a normalised convolution,
// sum_k w_k den_k L_k / sum_k w_k den_k (den_k the level's weight on the light). For tests and
// the LUT tool.
glm::vec3 prefilteredEmission(const PrefilteredLight& chain, glm::vec3 footprint);

}  // namespace penumbra::shading
