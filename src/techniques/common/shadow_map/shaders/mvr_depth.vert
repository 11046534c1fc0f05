// mvr: the occluders in one light sample's view (Heckbert & Herf 1997 as the VWSS paper's MVR).
// LAYERED: an instance a map, the geometry shader routes it to its layer (one draw for all
// maps); otherwise one draw per map with `layer` set. CENTRAL (reproject): the view from `eye`,
// the light centre.
#include "common_light.glsl"
#include "shadow_map_common.glsl"
layout(location = 0) in vec3 position;
layout(location = 2) in vec2 uv;  // for the alpha test (shading/shaders/alpha_test_depth.glsl)
out vec2 vUv;
#if defined(CENTRAL)
uniform vec3 eye;
#elif defined(LAYERED)
flat out int vLayer;
#else
uniform int layer;
#endif
void main() {
  vUv = uv;
#if defined(CENTRAL)
  gl_Position = mapClip(position, eye);
#else
#ifdef LAYERED
  int layer = gl_InstanceID;
  vLayer = layer;
#endif
  gl_Position = mapClip(position, samplePositions[layer].xyz);
#endif
}
