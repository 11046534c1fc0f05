// Depth maps from points by GPU compute (VWSS section 3.2, Listing 2): a thread a point, each
// thread splats its point into `layerCount` maps from `firstLayer` (1: serial, K: partially
// parallel, all: fully parallel). FROM_DEPTH_MAP (fragment reprojection, section 3): the points
// are the texels of the z-buffered central depth map, rebuilt from their depth.
#include "shadow_map_bindings.h"
#include "common_light.glsl"
#include "shadow_map_common.glsl"
#include "shadow_map_splat.glsl"
#include "compute_index.glsl"
layout(local_size_x = PENUMBRA_MAP_LOCAL_SIZE) in;
uniform int firstLayer;
uniform int layerCount;
#ifdef FROM_DEPTH_MAP
layout(binding = PENUMBRA_UNIT_CENTRAL_DEPTH) uniform sampler2D centralDepth;
uniform vec3 centralEye;
uniform int centralSize;
#else
#include "shadow_map_points.glsl"
#endif

void main() {
  uint i = globalIndex();
#ifdef FROM_DEPTH_MAP
  if (i >= uint(centralSize * centralSize)) return;
  ivec2 t = ivec2(int(i) % centralSize, int(i) / centralSize);
  float z = texelFetch(centralDepth, t, 0).r;
  if (!(z > 0.0)) return;  // nothing rasterised there
  float d = mapNear / z;
  vec2 ndc = viewTexelNdc(t, centralSize);
  vec3 p = centralEye + d * (mapAxis + mapTanHalf * (ndc.x * mapRight + ndc.y * mapUp));
#else
  if (i >= min(pointCount, pointCapacity)) return;
  vec3 p = loadPoint(i);
#endif
  splatPoint(p, firstLayer, layerCount);
}
