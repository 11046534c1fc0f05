// Writes the G-buffer. The normal is the geometric normal turned towards the camera, so
// surfaces are two-sided and the horizon rule (docs/architecture.md "Conventions") is the same for every
// technique and the reference. The shading normal (the BRDF's) is the
// interpolated vertex normal, normalised, turned to the geometric normal's side: a back face
// seen by the camera is shaded as its own front (two-sided, as the geometric normal), and a
// file whose normals point against its winding is shaded as if they did not. The material
// target holds the BRDF's parameters (shading/shaders/shading.h penumbraBrdf).
// The position is where the ray through the pixel centre meets the triangle's plane, not the
// interpolated vertex positions: interpolation errs by a few ULPs of the triangle's vertices
// (0.01 units near the camera on a 1e5-unit floor, off its own plane too when it is tilted),
// the intersection by a few ULPs of the point itself, which is what the evaluation point's
// epsilon (shared/numerics.h penumbraSurfaceEpsilon) assumes. Rays nearly in the plane keep the
// interpolated point.
#include "shared/numerics.h"
#include "shading/shaders/shading.h"
#include "shading/shaders/alpha_test.glsl"
in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
in vec3 vShading;
flat in float vPlane;

uniform vec3 cameraPosition;
uniform mat4 worldFromClip;  // inverse of the camera's clipFromWorld
uniform vec2 viewportSize;
uniform vec3 baseColor;
uniform float opacity;
uniform int hasTexture;
uniform int materialId;
uniform int brdfModel;  // PENUMBRA_BRDF_*
uniform float metallic;
uniform float roughness;
uniform int hasMetallicRoughnessTexture;
layout(binding = PENUMBRA_UNIT_MATERIAL_TEX) uniform sampler2D baseColorTexture;
layout(binding = PENUMBRA_UNIT_MATERIAL_MR_TEX) uniform sampler2D metallicRoughnessTexture;

layout(location = PENUMBRA_GBUF_POSITION) out vec4 outPosition;
layout(location = PENUMBRA_GBUF_NORMAL) out vec4 outNormal;
layout(location = PENUMBRA_GBUF_ALBEDO) out vec4 outAlbedo;
layout(location = PENUMBRA_GBUF_SHADING) out vec4 outShading;
layout(location = PENUMBRA_GBUF_MATERIAL) out vec4 outMaterial;

vec3 pixelRayPoint(vec3 face) {
  // glClipControl(GL_UPPER_LEFT): window y grows downwards in NDC (context.cpp).
  vec2 ndc = vec2(2.0 * gl_FragCoord.x / viewportSize.x - 1.0, 1.0 - 2.0 * gl_FragCoord.y / viewportSize.y);
  vec4 q = worldFromClip * vec4(ndc, 0.5, 1.0);
  vec3 dir = q.xyz / q.w - cameraPosition;
  float den = dot(face, dir);
  if (!(abs(den) > 1e-3 * length(dir))) return vPosition;
  float t = (vPlane - dot(face, cameraPosition)) / den;
  return t > 0.0 ? cameraPosition + dir * t : vPosition;
}

void main() {
  if (!penumbraSurfacePresent(baseColorTexture, vUv)) discard;  // alphaMode MASK: a hole
  vec3 face = normalize(vNormal);
  vec3 position = pixelRayPoint(face);
  vec3 n = face;
  if (dot(n, cameraPosition - position) < 0.0) n = -n;
  vec3 albedo = baseColor;
  if (hasTexture != 0) albedo *= texture(baseColorTexture, vUv).rgb;
  outPosition = vec4(position, 1.0);
  outNormal = vec4(n, float(materialId));
  outAlbedo = vec4(albedo, opacity);
  // Interpolation can shrink the normal to nothing between opposite vertex normals: then the face's.
  float len = length(vShading);
  vec3 s = len > 1e-6 ? vShading / len : n;
  outShading = vec4(dot(s, n) < 0.0 ? -s : s, 0.0);
  // glTF: the texture's B channel scales metallic, G roughness (linear data).
  vec2 mr = vec2(metallic, roughness);
  if (hasMetallicRoughnessTexture != 0) mr *= texture(metallicRoughnessTexture, vUv).bg;
  outMaterial = vec4(clamp(mr, 0.0, 1.0), float(brdfModel), 0.0);
}
