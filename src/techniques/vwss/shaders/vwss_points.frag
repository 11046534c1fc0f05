// vwss: every fragment of the central view (depth test off: all layers, section 3.1) is a point.
// Buffered: appended to the point buffer. UNBUFFERED: splatted into every map right here
// (section 3, Figure 3).
#include "common_light.glsl"
#include "shadow_map_common.glsl"
#include "shading/shaders/alpha_test_depth.glsl"
in vec3 vWorld;
#ifdef UNBUFFERED
#include "shadow_map_splat.glsl"
uniform int layerCount;
void main() {
  penumbraAlphaDiscard();
  splatPoint(vWorld, 0, layerCount);
}
#else
#include "shadow_map_points.glsl"
void main() {
  penumbraAlphaDiscard();
  uint i = atomicAdd(pointCount, 1u);
  if (i < pointCapacity) {
    pointData[3u * i] = vWorld.x;
    pointData[3u * i + 1u] = vWorld.y;
    pointData[3u * i + 2u] = vWorld.z;
  }
}
#endif
