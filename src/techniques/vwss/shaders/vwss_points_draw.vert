// vwss through the graphics pipeline (VWSS Figure 13, bottom): the same points drawn as GL_POINTS
// (1 pixel: the texel under the point, as the compute splat), one draw per map, z-buffered by
// the depth test into a depth-map layer.
#include "common_light.glsl"
#include "shadow_map_common.glsl"
#include "shadow_map_points.glsl"
uniform int layer;
out vec2 vUv;  // depth_only.frag's alpha test, off for points
void main() {
  vUv = vec2(0.0);
  vec3 p = loadPoint(uint(gl_VertexID));
  gl_Position = mapNonFinite(p) ? vec4(2.0, 2.0, 2.0, 1.0) : mapClip(p, samplePositions[layer].xyz);
}
