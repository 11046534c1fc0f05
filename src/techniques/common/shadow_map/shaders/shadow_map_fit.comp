// The shadow maps' frustum fitted on the GPU (techniques/shadow_map/maps.h FrameFit): reductions
// over the G-buffer, so no shadow-map technique reads it back.
//  PASS 0: a thread a G-buffer row: the sum (in doubles) and count of its surface positions.
//  PASS 1: one thread: the rows' sums, the receivers' centroid (isotropic lights' axis).
//  PASS 2: a thread a pixel: a receiver's depth beyond the views and its lateral reach from the
//          farthest view sideways; the widest receiver (lateral / depth) by atomicMax on its
//          bits (non-negative floats order as their bits), and the receivers outside the
//          frustum (nearer than the near plane, or wider than tanMax): counted and masked.
#include "compute_index.glsl"
#include "shadow_map_bindings.h"
layout(local_size_x = PENUMBRA_MAP_LOCAL_SIZE) in;
layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(std430, binding = PENUMBRA_SSBO_MAP_FIT) buffer Fit {
  dvec4 receiverSum;  // xyz: sum of the surface positions, w: their count
  uint tanHalfBits;
  uint outside;
  uint fitPad[6];
  dvec4 rows[];    // PASS 0's sums, a row each
};
layout(r32ui, binding = PENUMBRA_IMAGE_MAP_OUTSIDE) uniform writeonly uimage2D outsideMask;
uniform int pass;
uniform ivec2 size;
uniform vec3 lightCentre, mapAxis, mapRight, mapUp;
uniform float reachLateral, reachAxialMax, mapNear, tanMax;

// Written out and `precise`: the same float operations, in the same order, as the CPU's glm::dot.
float dot3(vec3 a, vec3 b) {
  precise float d = a.x * b.x + a.y * b.y;
  precise float e = d + a.z * b.z;
  return e;
}

void main() {
  uint i = globalIndex();
  if (pass == 0) {
    if (i >= uint(size.y)) return;
    dvec4 sum = dvec4(0.0);
    for (int x = 0; x < size.x; ++x) {
      vec4 g = texelFetch(gPosition, ivec2(x, int(i)), 0);
      if (g.w > 0.5) sum += dvec4(dvec3(g.xyz), 1.0);
    }
    rows[i] = sum;
    return;
  }
  if (pass == 1) {
    if (i != 0u) return;
    dvec4 sum = dvec4(0.0);
    for (int y = 0; y < size.y; ++y) sum += rows[y];
    receiverSum = sum;
    return;
  }
  if (i >= uint(size.x) * uint(size.y)) return;
  ivec2 px = ivec2(int(i % uint(size.x)), int(i / uint(size.x)));
  vec4 g = texelFetch(gPosition, px, 0);
  uint out_ = 0u;
  if (g.w > 0.5) {
    precise vec3 r = g.xyz - lightCentre;
    precise float depth = dot3(r, mapAxis) - reachAxialMax;
    precise float lateral = max(abs(dot3(r, mapRight)), abs(dot3(r, mapUp))) + reachLateral;
    // Behind a one-sided light too: it emits nothing there, but the visibility buffer (eq. 2)
    // counts its samples above the receiver's horizon, which no map holds; left unshadowed, so
    // counted (a light facing away from everything made every map technique return `none`'s
    // visibility while reporting no pixel).
    if (depth <= mapNear || lateral > tanMax * depth) {
      out_ = 1u;
      atomicAdd(outside, 1u);
    } else {
      atomicMax(tanHalfBits, floatBitsToUint(lateral / depth));
    }
  }
  imageStore(outsideMask, px, uvec4(out_));
}
