// Direct illumination of one light, added into the HDR target (DCS paper section 6).
// MODULATE: eq. 3, the light as a point at its centre carrying the whole light's power, times
// the RGB visibility of eq. 2. PER_SAMPLE: eq. 6, the sum over the pixel's light samples.
// RATIO: Heitz, Hill and McGuire 2018: the unshadowed term (in closed form for untextured rect,
// disk and sphere lights, shading/shaders/shading.h penumbraLightPolygon (Lambert's formula on the light's
// polygon), penumbraBallIrradiance; else the unshadowed sample sum) times the shadow ratio
// sum_k w_k T_k / sum_k w_k from the per-sample results, or V over its unshadowed value for a
// technique with V only. A pixel whose samples all miss (sum_k w_k = 0) gets ratio 0, as eq. 6.
// BRDF: shading/shaders/shading.h penumbraBrdf (Lambertian or the glTF metallic-roughness BRDF, from the
// G-buffer's material target), its cosine with the shading normal (the G-buffer's interpolated
// vertex normal), the horizon rule with the geometric one (docs/architecture.md "Conventions"). In the ratio
// mode the diffuse part's unshadowed term is Lambert's formula times the samples' mean of the
// diffuse BRDF (1 - F varies over the light; exact for LAMBERT); the specular part's is the LTC
// integral (shading/shaders/shading.h penumbraLightPolygon, the table of src/shading/ltc.h) times norm and Schlick's
// Fresnel at shading/shaders/shading.h penumbraLtcFresnelDirection for rect and disk lights, else the sample sum (sphere
// lights: no polygon). A textured rect or disk light's two integrals are each times its emission
// prefiltered for that lobe (Heitz et al. 2016 section 5.3: shading/shaders/shading.h penumbraPrefilterFootprint,
// src/shading/prefiltered_light.h); a textured sphere keeps the sample sum (docs/architecture.md "Lighting pipeline").
#include "shading/shaders/shading.h"
#include "common_light.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
layout(binding = PENUMBRA_UNIT_GBUF_ALBEDO) uniform sampler2D gAlbedo;
layout(binding = PENUMBRA_UNIT_GBUF_SHADING) uniform sampler2D gShading;
layout(binding = PENUMBRA_UNIT_GBUF_MATERIAL) uniform sampler2D gMaterial;
#if defined(MODULATE) || defined(RATIO)
layout(binding = PENUMBRA_UNIT_VISIBILITY) uniform sampler2D visibility;
#endif
#if defined(PER_SAMPLE) || defined(RATIO)
layout(binding = PENUMBRA_UNIT_SAMPLE_VIS) uniform sampler2DArray sampleVisibility;
#endif
#ifdef RATIO
uniform int ratioFromSamples;  // 1: the technique's per-sample results are bound
layout(binding = PENUMBRA_UNIT_LTC) uniform sampler2DArray ltcTable;  // layer 0 M^-1, layer 1 norm, fresnel
uniform float ltcSize;                                               // cells a side
uniform int lightPrefiltered;  // 1: the light's prefiltered emission is bound (a textured rect or disk)
layout(binding = PENUMBRA_UNIT_LIGHT_PREFILTERED) uniform sampler2DArray prefiltered;  // a layer a level
#ifdef EXACT_UNSHADOWED
// ratio-exact: the unshadowed term of this light integrated on the CPU (shading/light_integral.h,
// transmittance 1) instead of the closed forms and the LTC, so that a measurement never depends
// on the LTC's fit; without the light's colour and intensity, as `unshadowed` below.
layout(binding = PENUMBRA_UNIT_UNSHADOWED) uniform sampler2D exactUnshadowed;
#endif
uniform float prefilterSigma0;
uniform int prefilterLevels;
#endif
uniform vec3 eyePosition;

out vec4 outColor;

// The G-buffer's surface at a pixel: point, geometric and shading normal, the unit direction
// to the eye and the BRDF's parameters.
struct Surface {
  vec3 p, n, ns, v, base;
  float metallic, roughness;
  int model;
};

// The light's geometric term towards x, L_i cos(theta_s) [cos(theta_l)] / r^2 (0 below the
// geometric horizon), and the unit direction l to x.
vec3 geometricTerm(Surface s, vec3 x, vec3 luminance, out vec3 l) {
  l = normalize(x - s.p);
  return luminance * penumbraSampleGeometry(s.p, s.n, s.ns, x, lightNormal);
}

vec3 diffuseOf(Surface s, vec3 l) { return penumbraBrdfDiffuse(s.v, l, s.base, s.metallic, s.model); }
vec3 specularOf(Surface s, vec3 l) {
  return penumbraBrdfSpecular(s.ns, s.v, l, s.base, s.metallic, s.roughness, s.model);
}

// Sample i's share of the unshadowed integral, f L_i cos(theta_s) [cos(theta_l)] / r^2. Eq. 6
// and the ratio sum it.
vec3 sampleTerm(Surface s, uint i) {
  vec3 l;
  vec3 g = geometricTerm(s, samplePositions[i].xyz, sampleLuminance[i].rgb, l);
  return g * (diffuseOf(s, l) + specularOf(s, l));
}

#ifdef RATIO
// L_D, the emission averaged over the light with a lobe's weight, at a footprint (u, v, d) of
// penumbraPrefilterFootprint: every level mixed with penumbraPrefilterWeight as a normalised
// convolution (src/shading/prefiltered_light.h prefilteredEmission).
vec3 prefilteredEmission(vec3 footprint) {
  vec2 tc = penumbraPrefilterCoordinates(footprint.xy);
  vec3 num = vec3(0.0);
  float den = 0.0;
  for (int k = 0; k < prefilterLevels; ++k) {
    float w = penumbraPrefilterWeight(footprint.z, prefilterSigma0, k, prefilterLevels);
    vec4 t = textureLod(prefiltered, vec3(tc, float(k)), 0.0);
    num += w * t.a * t.rgb;
    den += w * t.a;
  }
  return den > 0.0 ? num / den : textureLod(prefiltered, vec3(tc, float(prefilterLevels - 1)), 0.0).rgb;
}

// The unshadowed terms in closed form where penumbra has one for this light and point: returns
// the integral of L cos(theta_s) [cos(theta_l)] / r^2 over the light (L the emission texture, 1
// untextured), -1 where there is none; and sets `specular` to the specular part's by LTC, -1
// where there is none.
vec3 closedForms(Surface s, out vec3 specular) {
  specular = vec3(-1.0);
  bool polygon = lightShape == PENUMBRA_LIGHT_RECT || lightShape == PENUMBRA_LIGHT_DISK;
  if (lightTextured != 0 && !(polygon && lightPrefiltered != 0)) return vec3(-1.0);
  if (lightShape == PENUMBRA_LIGHT_SPHERE) return vec3(penumbraBallIrradiance(s.p, s.n, s.ns, lightPosition, lightShapeRadius));
  if (!polygon) return vec3(-1.0);
  specular = vec3(0.0);
  if (!(dot(lightNormal, s.p - lightPosition) > 0.0)) return vec3(0.0);  // behind the light: it sees none of it
  bool glossy = s.model == PENUMBRA_BRDF_METALLIC_ROUGHNESS;
  vec2 uv = penumbraLtcCoordinates(s.roughness, dot(s.ns, s.v), ltcSize);
  vec4 minv = glossy ? textureLod(ltcTable, vec3(uv, 0.0), 0.0) : vec4(1.0, 0.0, 0.0, 1.0);
  vec3 bitangent = cross(lightNormal, lightTangent);
  vec2 size = lightShape == PENUMBRA_LIGHT_RECT ? lightHalfExtent : vec2(lightShapeRadius);
  vec2 e = penumbraLightPolygon(lightShape, s.p, s.n, s.ns, lightPosition, lightTangent, bitangent, size, glossy, s.v, minv);
  vec3 emittedDiffuse = vec3(1.0), emittedSpecular = vec3(1.0);
  if (lightTextured != 0) {
    vec3 x = penumbraLtcTangent(s.ns, s.v), y = cross(s.ns, x);
    vec4 identity = vec4(1.0, 0.0, 0.0, 1.0);
    emittedDiffuse = prefilteredEmission(penumbraPrefilterFootprint(s.p, lightPosition, lightTangent, bitangent, size,
                                                                    x, y, s.ns, identity));
    if (glossy)
      emittedSpecular = prefilteredEmission(penumbraPrefilterFootprint(s.p, lightPosition, lightTangent, bitangent,
                                                                       size, x, y, s.ns, minv));
  }
  if (glossy) {
    vec4 terms = textureLod(ltcTable, vec3(uv, 1.0), 0.0);
    vec3 l = penumbraLtcFresnelDirection(lightShape, s.p, s.ns, s.v, lightPosition, lightNormal, lightTangent, bitangent,
                                         size, penumbraAlpha(s.roughness));
    specular = e.y * terms.x * penumbraSchlick(penumbraF0(s.base, s.metallic), dot(s.v, normalize(s.v + l))) *
               emittedSpecular;
  }
  return e.x * emittedDiffuse;
}

vec3 ratioOf(vec3 a, vec3 b) {
  return vec3(b.r > 0.0 ? a.r / b.r : 0.0, b.g > 0.0 ? a.g / b.g : 0.0, b.b > 0.0 ? a.b / b.b : 0.0);
}
#endif

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 p = texelFetch(gPosition, px, 0);
  if (p.w == 0.0) discard;
  vec4 m = texelFetch(gMaterial, px, 0);
  Surface s = Surface(p.xyz, texelFetch(gNormal, px, 0).xyz, texelFetch(gShading, px, 0).xyz,
                      normalize(eyePosition - p.xyz), texelFetch(gAlbedo, px, 0).rgb, m.r, m.g, int(m.b + 0.5));
#ifdef MODULATE
  // The centre's horizon as the samples' (eq. 3 treats the light as a point at its centre).
  vec3 l;
  vec3 g = geometricTerm(s, lightPosition, vec3(1.0), l);
  vec3 v = texelFetch(visibility, px, 0).rgb;
  outColor = vec4((diffuseOf(s, l) + specularOf(s, l)) * lightEmission * lightScale * v * g, 1.0);
#elif defined(RATIO)
  uint base = pixelSampleBase(px);
  vec3 weights = vec3(0.0), shadowed = vec3(0.0), unshadowedV = vec3(0.0);
  vec3 diffuse = vec3(0.0), specular = vec3(0.0), diffuseUnit = vec3(0.0);
  float geometric = 0.0;
  for (uint k = 0u; k < sampleCount; ++k) {
    vec3 l;
    vec3 g1 = geometricTerm(s, samplePositions[base + k].xyz, vec3(1.0), l);
    vec3 g = g1 * sampleLuminance[base + k].rgb;
    vec3 bd = diffuseOf(s, l);
    vec3 fd = g * bd, fs = g * specularOf(s, l);
    weights += fd + fs;
    diffuse += fd;
    specular += fs;
    diffuseUnit += g1 * bd;
    geometric += g1.x;
    if (aboveHorizon(s.p, s.n, samplePositions[base + k].xyz)) unshadowedV += sampleLuminance[base + k].rgb;
    if (ratioFromSamples != 0) shadowed += (fd + fs) * texelFetch(sampleVisibility, ivec3(px, int(k)), 0).r;
  }
  vec3 ltc;
  vec3 closed = closedForms(s, ltc);
  vec3 centre;
  geometricTerm(s, lightPosition, vec3(1.0), centre);
  // The diffuse BRDF's mean over the samples, weighted by their geometric terms without the
  // emission (its value at the light's centre where no sample is above the horizon).
  vec3 diffuseMean = geometric > 0.0 ? diffuseUnit / geometric : diffuseOf(s, centre);
  vec3 unshadowed = (closed.x >= 0.0 ? closed * diffuseMean : diffuse * sampleWeight) +
                    (ltc.x >= 0.0 ? ltc : specular * sampleWeight);
#ifdef EXACT_UNSHADOWED
  unshadowed = texelFetch(exactUnshadowed, px, 0).rgb;
#endif
  vec3 ratio = ratioFromSamples != 0 ? ratioOf(shadowed, weights)
                                     : ratioOf(texelFetch(visibility, px, 0).rgb * float(sampleCount), unshadowedV);
  outColor = vec4(lightEmission * unshadowed * ratio, 1.0);
#else
  uint base = pixelSampleBase(px);
  vec3 sum = vec3(0.0);
  for (uint k = 0u; k < sampleCount; ++k)
    sum += sampleTerm(s, base + k) * texelFetch(sampleVisibility, ivec3(px, int(k)), 0).r;
  outColor = vec4(lightEmission * sampleWeight * sum, 1.0);
#endif
}
