// The gather step of interleaved sampling (DCS paper 5.2 and Algorithm 2, after Segovia et al.
// 2006, without their image split): each pixel averages a K x K window, which holds every one
// of the K*K sample sets once, over the neighbours on the same surface: a neighbour counts when
// its normal is within ~25 degrees of the pixel's and it lies within 2% of the camera distance
// of the pixel's tangent plane (the normal and depth discontinuity test). Applied to the
// visibility buffer (eq. 3 shading) or to one light's shaded contribution (eq. 6).
layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
layout(binding = PENUMBRA_UNIT_FILTER_SOURCE) uniform sampler2D filterSource;
uniform int interleaveK;
uniform vec3 eyePosition;

out vec4 outValue;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 p = texelFetch(gPosition, px, 0);
  if (p.w == 0.0) {
    outValue = texelFetch(filterSource, px, 0);
    return;
  }
  vec3 n = texelFetch(gNormal, px, 0).xyz;
  float tolerance = 0.02 * distance(eyePosition, p.xyz);
  ivec2 size = textureSize(filterSource, 0);
  ivec2 lo = px - ivec2((interleaveK - 1) / 2);
  vec4 sum = vec4(0.0);
  float weight = 0.0;
  for (int dy = 0; dy < interleaveK; ++dy) {
    for (int dx = 0; dx < interleaveK; ++dx) {
      ivec2 q = lo + ivec2(dx, dy);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      vec4 pq = texelFetch(gPosition, q, 0);
      if (pq.w == 0.0) continue;
      if (dot(texelFetch(gNormal, q, 0).xyz, n) < 0.9) continue;
      if (abs(dot(n, pq.xyz - p.xyz)) > tolerance) continue;
      sum += texelFetch(filterSource, q, 0);
      weight += 1.0;
    }
  }
  outValue = sum / weight;  // the pixel itself always counts
}
