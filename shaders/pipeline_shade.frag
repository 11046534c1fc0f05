// Direct illumination of one light, added into the HDR target (DCS paper section 6).
// MODULATE: eq. 3, the light as a point at its centre carrying the whole light's power, times
// the RGB visibility of eq. 2. PER_SAMPLE: eq. 6, the sum over the pixel's light samples.
// BRDF: Lambertian, albedo / pi; its cosine with the shading normal (the G-buffer's interpolated
// vertex normal), the horizon rule with the geometric one (README "Conventions").
#include "common_light.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
layout(binding = PENUMBRA_UNIT_GBUF_ALBEDO) uniform sampler2D gAlbedo;
layout(binding = PENUMBRA_UNIT_GBUF_SHADING) uniform sampler2D gShading;
#ifdef MODULATE
layout(binding = PENUMBRA_UNIT_VISIBILITY) uniform sampler2D visibility;
#else
layout(binding = PENUMBRA_UNIT_SAMPLE_VIS) uniform sampler2DArray sampleVisibility;
#endif

out vec4 outColor;

const float kInvPi = 0.31830988618379067;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 p = texelFetch(gPosition, px, 0);
  if (p.w == 0.0) discard;
  vec3 n = texelFetch(gNormal, px, 0).xyz;
  vec3 ns = texelFetch(gShading, px, 0).xyz;
  vec3 brdf = texelFetch(gAlbedo, px, 0).rgb * kInvPi;
#ifdef MODULATE
  vec3 d = lightPosition - p.xyz;
  float r2 = dot(d, d);
  vec3 l = d * inversesqrt(r2);
  // The centre's horizon as the samples' (eq. 3 treats the light as a point at its centre).
  float g = aboveHorizon(p.xyz, n, lightPosition) ? max(dot(ns, l), 0.0) * emitterCosine(-l) / r2 : 0.0;
  vec3 v = texelFetch(visibility, px, 0).rgb;
  outColor = vec4(brdf * lightEmission * lightScale * v * g, 1.0);
#else
  uint base = pixelSampleBase(px);
  vec3 sum = vec3(0.0);
  for (uint k = 0u; k < sampleCount; ++k) {
    vec3 x = samplePositions[base + k].xyz;
    if (!aboveHorizon(p.xyz, n, x)) continue;
    vec3 d = x - p.xyz;
    float r2 = dot(d, d);
    vec3 l = d * inversesqrt(r2);
    float t = texelFetch(sampleVisibility, ivec3(px, int(k)), 0).r;
    sum += sampleLuminance[base + k].rgb * (t * max(dot(ns, l), 0.0) * emitterCosine(-l) / r2);
  }
  outColor = vec4(brdf * lightEmission * sampleWeight * sum, 1.0);
#endif
}
