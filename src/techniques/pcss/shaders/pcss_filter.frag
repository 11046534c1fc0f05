// pcss separable filters of a single-channel texture (one direction a pass):
//  * GAUSSIAN: the 7-tap Gaussian of sigma 3 (Sterna 2.2's 7 x 7 blur of the penumbra mask,
//    and of the min-filtered map, 2.3);
//  * MAX_FILTER: the largest value within `radius` texels: on reversed depth, the nearest
//    occluder (Sterna 2.3's min filter of the shadow map).
#include "single_view_bindings.h"
layout(binding = PENUMBRA_UNIT_PCSS_SOURCE) uniform sampler2D source;
uniform ivec2 direction;
uniform int radius;
out vec4 outValue;
void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(source, 0) - 1;
#ifdef MAX_FILTER
  float v = 0.0;
  for (int i = -radius; i <= radius; ++i) v = max(v, texelFetch(source, clamp(px + i * direction, ivec2(0), last), 0).r);
#else
  float v = 0.0, w = 0.0;
  for (int i = -3; i <= 3; ++i) {
    float g = exp(-float(i * i) / 18.0);
    v += g * texelFetch(source, clamp(px + i * direction, ivec2(0), last), 0).r;
    w += g;
  }
  v /= w;
#endif
  outValue = vec4(v);
}
