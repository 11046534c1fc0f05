// Semi-opaque occluders of the multi-view maps (src/techniques/shadow_map/maps.h): every
// semi-opaque fragment of a sample's view takes the next of its texel's K entries (imageAtomicAdd
// on the texel's count) and stores its reversed depth z = near / d with the low 8 bits replaced
// by its opacity in 1/255 steps (z keeps 15 bits of mantissa: a relative depth error below
// 4e-5, far inside the depth bias). The most entries any texel asked for goes to the status
// image, so that a frame whose K was too small is redone with enough (no entry is dropped).
#include "shadow_map_bindings.h"
layout(binding = PENUMBRA_IMAGE_SEMI_COUNT, r32ui) uniform coherent uimage2DArray semiCount;
layout(binding = PENUMBRA_IMAGE_SEMI_LAYERS, r32ui) uniform writeonly uimage2DArray semiLayers;
layout(binding = PENUMBRA_IMAGE_SEMI_STATUS, r32ui) uniform coherent uimage2D semiStatus;
uniform float opacity;
uniform int semiSlots;  // K
flat in int gLayer;     // the map (src/techniques/common/shadow_map/shaders/mvr_depth.geom)
void main() {
  ivec3 t = ivec3(ivec2(gl_FragCoord.xy), gLayer);
  uint slot = imageAtomicAdd(semiCount, t, 1u);
  imageAtomicMax(semiStatus, ivec2(0), slot + 1u);
  if (slot >= uint(semiSlots)) return;
  uint code = uint(clamp(round(opacity * 255.0), 1.0, 254.0));
  uint entry = (floatBitsToUint(gl_FragCoord.z) & 0xFFFFFF00u) | code;
  imageStore(semiLayers, ivec3(t.xy, t.z * semiSlots + int(slot)), uvec4(entry));
}
