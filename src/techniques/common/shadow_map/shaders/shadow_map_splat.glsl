// Point rendering into the multi-view maps (VWSS section 3.2, Listing 2; fragment reprojection
// section 3.1.1): a world point is projected into layers [first, first + count) of the R32UI
// map array, snapped to the nearest texel and z-buffered with imageAtomicMax on the bits of its
// reversed depth (shadow_map_common.glsl). UNSYNCHRONIZED: a plain store, the last writer wins
// (fragment reprojection section 3.2's unsynchronised variant).
// Hard case 22: a non-finite point, a point behind or on a sample's near plane (w <= near,
// including w = -0.0 and NaN: the comparison is false) and one outside the frustum are skipped,
// so the map keeps what it had; the stored depth is near / w > 0, never -0.0 or NaN.
#include "shadow_map_bindings.h"
layout(binding = PENUMBRA_IMAGE_SHADOW_MAPS, r32ui) uniform coherent uimage2DArray shadowMaps;

void splatPoint(vec3 p, int first, int count) {
  if (mapNonFinite(p)) return;
  for (int l = first; l < first + count; ++l) {
    vec4 c = mapClip(p, samplePositions[l].xyz);
    if (!(c.w > mapNear)) continue;
    vec2 ndc = c.xy / c.w;
    if (!all(lessThan(abs(ndc), vec2(1.0)))) continue;
    ivec3 t = ivec3(viewTexel(ndc, mapSize), l);
    uint z = floatBitsToUint(mapNear / c.w);
#ifdef UNSYNCHRONIZED
    imageStore(shadowMaps, t, uvec4(z));
#else
    imageAtomicMax(shadowMaps, t, z);
#endif
  }
}
