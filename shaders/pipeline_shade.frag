// Direct illumination of one light, added into the HDR target (DCS paper section 6).
// MODULATE: eq. 3, the light as a point at its centre carrying the whole light's power, times
// the RGB visibility of eq. 2. PER_SAMPLE: eq. 6, the sum over the pixel's light samples.
// RATIO: Heitz, Hill and McGuire 2018: the unshadowed term (exact for untextured rect lights,
// shared.h penumbraRectIrradiance, and for untextured sphere lights wholly above the horizon,
// penumbraBallIrradiance; else the unshadowed sample sum) times the shadow ratio
// sum_k w_k T_k / sum_k w_k from the per-sample results, or V over its unshadowed value for a
// technique with V only. A pixel whose samples all miss (sum_k w_k = 0) gets ratio 0, as eq. 6.
// BRDF: Lambertian, albedo / pi; its cosine with the shading normal (the G-buffer's interpolated
// vertex normal), the horizon rule with the geometric one (README "Conventions").
#include "common_light.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
layout(binding = PENUMBRA_UNIT_GBUF_ALBEDO) uniform sampler2D gAlbedo;
layout(binding = PENUMBRA_UNIT_GBUF_SHADING) uniform sampler2D gShading;
#if defined(MODULATE) || defined(RATIO)
layout(binding = PENUMBRA_UNIT_VISIBILITY) uniform sampler2D visibility;
#endif
#if defined(PER_SAMPLE) || defined(RATIO)
layout(binding = PENUMBRA_UNIT_SAMPLE_VIS) uniform sampler2DArray sampleVisibility;
#endif
#ifdef RATIO
uniform int ratioFromSamples;  // 1: the technique's per-sample results are bound
#endif

out vec4 outColor;

const float kInvPi = 0.31830988618379067;

// Sample i's share of the unshadowed integral, L_i cos(theta_s) [cos(theta_l)] / r^2: 0 below
// the geometric horizon, the cosine with the shading normal. Eq. 6 and the ratio sum it.
vec3 sampleTerm(vec3 p, vec3 n, vec3 ns, uint i) {
  vec3 x = samplePositions[i].xyz;
  if (!aboveHorizon(p, n, x)) return vec3(0.0);
  vec3 d = x - p;
  float r2 = dot(d, d);
  vec3 l = d * inversesqrt(r2);
  return sampleLuminance[i].rgb * (max(dot(ns, l), 0.0) * emitterCosine(-l) / r2);
}

#ifdef RATIO
// The unshadowed integral in closed form where penumbra has one for this light and point, else -1.
float closedFormIrradiance(vec3 p, vec3 n, vec3 ns) {
  if (lightTextured != 0) return -1.0;
  if (lightShape == PENUMBRA_LIGHT_RECT)
    return dot(lightNormal, p - lightPosition) > 0.0
               ? penumbraRectIrradiance(p, n, ns, lightPosition, lightTangent, cross(lightNormal, lightTangent),
                                        lightHalfExtent)
               : 0.0;
  if (lightShape == PENUMBRA_LIGHT_SPHERE) return penumbraBallIrradiance(p, n, ns, lightPosition, lightShapeRadius);
  return -1.0;
}

vec3 ratioOf(vec3 a, vec3 b) {
  return vec3(b.r > 0.0 ? a.r / b.r : 0.0, b.g > 0.0 ? a.g / b.g : 0.0, b.b > 0.0 ? a.b / b.b : 0.0);
}
#endif

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
#elif defined(RATIO)
  uint base = pixelSampleBase(px);
  vec3 weights = vec3(0.0), shadowed = vec3(0.0), unshadowedV = vec3(0.0);
  for (uint k = 0u; k < sampleCount; ++k) {
    vec3 w = sampleTerm(p.xyz, n, ns, base + k);
    weights += w;
    if (aboveHorizon(p.xyz, n, samplePositions[base + k].xyz)) unshadowedV += sampleLuminance[base + k].rgb;
    if (ratioFromSamples != 0) shadowed += w * texelFetch(sampleVisibility, ivec3(px, int(k)), 0).r;
  }
  float closed = closedFormIrradiance(p.xyz, n, ns);
  vec3 unshadowed = closed >= 0.0 ? vec3(closed) : weights * sampleWeight;
  vec3 ratio = ratioFromSamples != 0 ? ratioOf(shadowed, weights)
                                     : ratioOf(texelFetch(visibility, px, 0).rgb * float(sampleCount), unshadowedV);
  outColor = vec4(brdf * lightEmission * unshadowed * ratio, 1.0);
#else
  uint base = pixelSampleBase(px);
  vec3 sum = vec3(0.0);
  for (uint k = 0u; k < sampleCount; ++k)
    sum += sampleTerm(p.xyz, n, ns, base + k) * texelFetch(sampleVisibility, ivec3(px, int(k)), 0).r;
  outColor = vec4(brdf * lightEmission * sampleWeight * sum, 1.0);
#endif
}
