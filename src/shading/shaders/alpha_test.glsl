// The alpha test in a fragment shader (shading/shaders/alpha_test.h): GpuScene sets `alphaTest`,
// `alphaFactor` and `alphaCutoff` per draw and binds the material's base colour texture to
// PENUMBRA_UNIT_MATERIAL_TEX; a fragment where the surface is absent is discarded. The vertex
// stage (or, with LAYERED, the geometry stage) passes the texture coordinate.
#include "shading/shaders/alpha_test.h"
uniform int alphaTest;
uniform float alphaFactor;
uniform float alphaCutoff;

bool penumbraSurfacePresent(sampler2D tex, vec2 uv) {
  if (alphaTest == 0) return true;
  ivec2 size = textureSize(tex, 0);
  vec2 first, weight;
  penumbraAlphaTexels(uv, vec2(size), first, weight);
  ivec2 a = ivec2(penumbraWrapTexel(first, vec2(size))), b = ivec2(penumbraWrapTexel(first + 1.0, vec2(size)));
  return penumbraAlphaPasses(texelFetch(tex, a, 0).a, texelFetch(tex, ivec2(b.x, a.y), 0).a,
                             texelFetch(tex, ivec2(a.x, b.y), 0).a, texelFetch(tex, b, 0).a, weight, alphaFactor,
                             alphaCutoff);
}
