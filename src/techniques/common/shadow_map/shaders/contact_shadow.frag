// Contact shadows: a short march in screen space from the receiver towards the light, through
// the camera's G-buffer, as engines add on top of a shadow map where the map's resolution fails:
// at contact (Days Gone's, integrated in UE: [UE-Contact]). Ours marches towards the pixel's
// light samples (light_rays.glsl), `contactRays` of them, each `contactSteps` steps over a world
// length that spans `contactLength` of the screen's height at the receiver's depth. A step is
// hidden when the G-buffer's surface at its pixel is nearer the camera than the step by more than
// the receiver's epsilon and less than `contactThickness` x the step's distance to the camera;
// the ray is then blocked; points of the receiver's own plane are skipped. The factor (the unblocked rays' share of the luminance) multiplies the
// map technique's visibility (blending: dst * src): contact and map shadows are taken as
// independent, as the engines combine them.
#include "shared/numerics.h"
#include "common_light.glsl"
#include "light_rays.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
uniform mat4 clipFromWorld;
uniform vec3 eyePosition;
uniform float tanHalfFovY;
uniform int contactRays;
uniform int contactSteps;
uniform float contactLength;
uniform float contactThickness;

out vec4 outFactor;

// 1 where the march from o towards q (over `len` world units) meets no surface in the G-buffer.
float march(vec3 o, vec3 p, vec3 n, vec3 q, float len, float offset, ivec2 size) {
  vec3 dir = normalize(q - o);
  len = min(len, distance(o, q));
  for (int s = 0; s < contactSteps; ++s) {
    vec3 x = o + dir * (len * (float(s) + offset) / float(contactSteps));
    vec4 c = clipFromWorld * vec4(x, 1.0);
    if (c.w <= 0.0) break;
    vec2 ndc = c.xy / c.w;
    if (any(greaterThan(abs(ndc), vec2(1.0)))) break;  // off screen: the G-buffer knows nothing
    // The pixel as the rasteriser assigned it (glClipControl GL_UPPER_LEFT flips y).
    ivec2 px = clamp(ivec2(floor(vec2(ndc.x * 0.5 + 0.5, 0.5 - 0.5 * ndc.y) * vec2(size))), ivec2(0), size - 1);
    vec4 g = texelFetch(gPosition, px, 0);
    if (g.w == 0.0) continue;
    // The receiver's own plane cannot shadow it: a step's pixel that shows a point of that plane
    // (its neighbour on a face seen at a slant, nearer the camera by a pixel's footprint) is skipped.
    if (abs(dot(n, g.xyz - p)) <= 1e-3 * distance(g.xyz, p) + penumbraSurfaceEpsilon(p)) continue;
    float dx = distance(x, eyePosition), ds = distance(g.xyz, eyePosition);
    float eps = 4.0 * (penumbraSurfaceEpsilon(x) + penumbraSurfaceEpsilon(eyePosition));
    if (ds < dx - eps && ds > dx * (1.0 - contactThickness)) return 0.0;
  }
  return 1.0;
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 g = texelFetch(gPosition, px, 0);
  if (g.w == 0.0) { outFactor = vec4(1.0); return; }
  vec3 p = g.xyz, n = texelFetch(gNormal, px, 0).xyz;
  vec3 o = penumbraShadowOrigin(p, n, eyePosition);
  ivec2 size = textureSize(gPosition, 0);
  // The world length of contactLength of the screen's height at the receiver's view depth.
  float len = contactLength * 2.0 * tanHalfFovY * (clipFromWorld * vec4(p, 1.0)).w;
  uint base = pixelSampleBase(px);
  int count = int(sampleCount);
  int traced = raysTraced(contactRays, count);
  float noise = interleavedGradientNoise(vec2(px) + 0.5);
  int first = int(noise * float(count));
  float offset = fract(noise * 7.0 + 0.5);
  vec3 total = vec3(0.0), lit = vec3(0.0);
  for (int i = 0; i < traced; ++i) {
    uint k = raySample(i, traced, count, first);
    vec3 q = samplePositions[base + k].xyz;
    if (!aboveHorizon(p, n, q)) continue;
    vec3 l = sampleLuminance[base + k].rgb;
    total += l;
    lit += l * march(o, p, n, q, len, offset, size);
  }
  outFactor = vec4(arrivingShare(lit, total), 1.0);
}
