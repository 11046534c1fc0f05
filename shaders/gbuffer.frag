// Writes the G-buffer. The normal is the geometric normal turned towards the camera, so
// surfaces are two-sided and the horizon rule (README "Conventions") is the same for every
// technique and the reference.
in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;

uniform vec3 cameraPosition;
uniform vec3 baseColor;
uniform float opacity;
uniform int hasTexture;
uniform int materialId;
layout(binding = PENUMBRA_UNIT_MATERIAL_TEX) uniform sampler2D baseColorTexture;

layout(location = PENUMBRA_GBUF_POSITION) out vec4 outPosition;
layout(location = PENUMBRA_GBUF_NORMAL) out vec4 outNormal;
layout(location = PENUMBRA_GBUF_ALBEDO) out vec4 outAlbedo;

void main() {
  vec3 n = normalize(vNormal);
  if (dot(n, cameraPosition - vPosition) < 0.0) n = -n;
  vec3 albedo = baseColor;
  if (hasTexture != 0) albedo *= texture(baseColorTexture, vUv).rgb;
  outPosition = vec4(vPosition, 1.0);
  outNormal = vec4(n, float(materialId));
  outAlbedo = vec4(albedo, opacity);
}
