// vwss point generation (VWSS section 3.1, eq. 1-2): the occluders rasterised once from the
// central view, the light centre moved back along the light normal so that its frustum holds
// every sample's (`centralEye`, near plane `centralNear` in the plane of the light). No storage
// blocks here: the fragment stage writes the point buffer (shared/shared.h, bindings).
#include "shadow_map_common.glsl"
layout(location = 0) in vec3 position;
layout(location = 2) in vec2 uv;  // for the alpha test (shading/shaders/alpha_test_depth.glsl)
out vec2 vUv;
uniform vec3 centralEye;
uniform float centralNear;
out vec3 vWorld;
void main() {
  vWorld = position;
  vUv = uv;
  gl_Position = viewClip(position, centralEye, centralNear);
}
