// Visibility buffer (DCS eq. 2) from a per-pixel occlusion decision that holds for the whole
// light (hard shadows from the light centre: COUNTER), or no occlusion at all (UNSHADOWED):
//   V_rgb = 1/N sum_k L_k * [sample k above the horizon] * visible.
#include "common_light.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
#ifdef COUNTER
layout(binding = PENUMBRA_UNIT_COUNTER) uniform sampler2D counter;
#endif

out vec4 outVisibility;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 p = texelFetch(gPosition, px, 0);
  if (p.w == 0.0) { outVisibility = vec4(0.0); return; }
  float visible = 1.0;
#ifdef COUNTER
  // The count is a winding number (an integer); anything but 0 is inside a shadow volume.
  visible = abs(texelFetch(counter, px, 0).r) < 0.5 ? 1.0 : 0.0;
#endif
  vec3 n = texelFetch(gNormal, px, 0).xyz;
  uint base = pixelSampleBase(px);
  vec3 v = vec3(0.0);
  for (uint k = 0u; k < sampleCount; ++k)
    if (aboveHorizon(p.xyz, n, samplePositions[base + k].xyz)) v += sampleLuminance[base + k].rgb;
  outVisibility = vec4(v * (visible / float(sampleCount)), 1.0);
}
