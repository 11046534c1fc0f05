// The alpha test of glTF 2.0 alphaMode MASK (section 3.9.4, "Alpha Coverage"): a surface point is
// there where the material's constant alpha (baseColorFactor.a) times its base colour texture's
// alpha is at least alphaCutoff, and absent (no occluder, no camera hit) elsewhere. One decision
// for every consumer: the G-buffer and the shadow-map depth passes (GLSL,
// shading/shaders/alpha_test.glsl) and the Embree reference's hit filter (C++, through
// shading/shading_shared.hpp), so that the camera, the maps and the rays see the same holes.
//
// The texture's alpha at `uv` is bilinear between the four texels around it, repeat-wrapped, as
// GL_LINEAR samples a texture without mipmaps (OpenGL 4.6 section 8.14.2, eq. 8.10-8.11, i0 =
// floor(u w - 1/2)); computed here in float from fetched texels rather than by the sampler, whose
// weights have 8 fractional bits on llvmpipe, so that both languages compute the same numbers.
#ifndef PENUMBRA_ALPHA_TEST_H
#define PENUMBRA_ALPHA_TEST_H

// Where `uv` falls among the texels of a texture of `size` texels: the lower-left texel of the
// four (unwrapped) and the weights towards the next column and row.
PENUMBRA_FN void penumbraAlphaTexels(vec2 uv, vec2 size, PENUMBRA_OUT(vec2) first, PENUMBRA_OUT(vec2) weight) {
  vec2 t = uv * size - vec2(0.5f);
  first = floor(t);
  weight = t - first;
}

// Texel column/row `t` wrapped into [0, size) (GL_REPEAT), as floats: t - size floor(t / size),
// clamped against that expression's rounding for large t.
PENUMBRA_FN vec2 penumbraWrapTexel(vec2 t, vec2 size) {
  vec2 w = t - size * floor(t / size);
  return clamp(w, vec2(0.0f), size - vec2(1.0f));
}

// Whether the surface is there, from the four texels' alphas (a00 at `first`, a10 one column
// on, a01 one row on) and the weights of penumbraAlphaTexels.
PENUMBRA_FN bool penumbraAlphaPasses(float a00, float a10, float a01, float a11, vec2 weight, float factor,
                                     float cutoff) {
  float bottom = a00 + (a10 - a00) * weight.x;
  float top = a01 + (a11 - a01) * weight.x;
  float alpha = bottom + (top - bottom) * weight.y;
  return alpha * factor >= cutoff;
}

#endif
