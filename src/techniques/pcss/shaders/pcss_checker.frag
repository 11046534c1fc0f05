// pcss checkerboard upsample (Sterna 3): the shadow pass computed the pixels with x + y even
// into a half-width target; the others take the mean of their four computed neighbours,
// weighted by depth agreement (neighbours on another surface, a bilateral test on the
// G-buffer's position and normal, count 1/1000).
#include "single_view_bindings.h"
layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
layout(binding = PENUMBRA_UNIT_PCSS_SOURCE) uniform sampler2D checker;
uniform vec3 eyePosition;
out vec4 outVisibility;

vec4 computed(ivec2 px) { return texelFetch(checker, ivec2((px.x - (px.y & 1)) / 2, px.y), 0); }

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  if (((px.x + px.y) & 1) == 0) { outVisibility = computed(px); return; }
  vec4 g = texelFetch(gPosition, px, 0);
  if (g.w == 0.0) { outVisibility = vec4(0.0); return; }
  vec3 n = texelFetch(gNormal, px, 0).xyz;
  float tolerance = 0.02 * length(g.xyz - eyePosition);
  ivec2 size = textureSize(gPosition, 0);
  const ivec2 offsets[4] = ivec2[](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
  vec4 sum = vec4(0.0);
  float weight = 0.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 q = px + offsets[i];
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    vec4 gq = texelFetch(gPosition, q, 0);
    if (gq.w == 0.0) continue;
    bool same = length(gq.xyz - g.xyz) < tolerance && dot(texelFetch(gNormal, q, 0).xyz, n) > 0.9;
    float w = same ? 1.0 : 1e-3;
    sum += w * computed(q);
    weight += w;
  }
  outVisibility = weight > 0.0 ? sum / weight : vec4(0.0, 0.0, 0.0, 1.0);
}
