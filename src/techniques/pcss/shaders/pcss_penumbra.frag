// pcss penumbra mask (Sterna 2.2): at quarter resolution (half width, half height), the
// blocker search of the full-resolution pixel at the low-resolution pixel's corner, with the
// search kernel scaled (kernelScale, 1.2-1.6), written as the penumbra's uv radius. No blocker:
// 0, or with NO_BLOCKER_ONE the largest radius (the search radius), so that blurring does not
// shrink the penumbrae next to lit areas (Sterna's "1 when no blocker" option).
#include "pcss_common.glsl"
out vec4 outRadius;
void main() {
  ivec2 px = 2 * ivec2(gl_FragCoord.xy);
  vec3 p, n;
  if (texelFetch(gPosition, px, 0).w == 0.0) { outRadius = vec4(0.0); return; }
  Receiver r = receiverOf(px, p, n);
  if (!r.inView) { outRadius = vec4(0.0); return; }
  float phi = TWO_PI * interleavedGradientNoise(vec2(px) + 0.5);
  float blocker = averageBlockerDepth(r, phi);
#ifdef NO_BLOCKER_ONE
  float radius = blocker < 0.0 ? searchRadius(r) : penumbraRadius(r, blocker);
#else
  float radius = blocker < 0.0 ? 0.0 : penumbraRadius(r, blocker);
#endif
  outRadius = vec4(radius);
}
