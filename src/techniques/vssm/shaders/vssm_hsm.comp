// vssm min-max hierarchical shadow map (VSSM Algorithm 1 L4, section 6.1: mip-maps): level 0
// holds each texel's normalised depth twice (min, max); level k the min and max of the 2 x 2
// texels under it. All levels in one buffer, level k at offset sum_{l<k} (size >> l)^2.
#include "single_view_bindings.h"
#include "compute_index.glsl"
layout(local_size_x = PENUMBRA_MAP_LOCAL_SIZE) in;
layout(std430, binding = PENUMBRA_SSBO_VSSM_HSM) buffer Hsm { vec2 hsm[]; };
layout(binding = PENUMBRA_UNIT_PCSS_DEPTH) uniform sampler2D depthRaw;
uniform int satSize;  // level 0 size (a power of two)
uniform int level;
uniform float mapNear;
#include "vssm_common.glsl"

int levelOffset(int l) {
  int offset = 0;
  for (int i = 0; i < l; ++i) offset += (satSize >> i) * (satSize >> i);
  return offset;
}

void main() {
  int i = int(globalIndex());
  int size = satSize >> level;
  if (i >= size * size) return;
  ivec2 t = ivec2(i % size, i / size);
  if (level == 0) {
    float z = texelFetch(depthRaw, t, 0).r;
    float x = normalisedMapDepth(z, mapNear);
    hsm[i] = vec2(x);
    return;
  }
  int below = levelOffset(level - 1), here = levelOffset(level), belowSize = size * 2;
  vec2 a = hsm[below + (2 * t.y) * belowSize + 2 * t.x], b = hsm[below + (2 * t.y) * belowSize + 2 * t.x + 1];
  vec2 c = hsm[below + (2 * t.y + 1) * belowSize + 2 * t.x], d = hsm[below + (2 * t.y + 1) * belowSize + 2 * t.x + 1];
  hsm[here + i] = vec2(min(min(a.x, b.x), min(c.x, d.x)), max(max(a.y, b.y), max(c.y, d.y)));
}
