// smrt shadow pass (src/techniques/smrt): shadow-map ray tracing as engines ship it for area
// lights ([UE-VSM] "soft shadows with shadow map ray tracing", [EEVEE-Shadows]), written from
// their published descriptions. Per pixel, `rays` rays from the receiver towards points of the
// light (the pixel's own light samples, so the reference integrates the same points), each
// marched in `steps` steps through the one depth map seen from the light centre. A ray point is
// "behind the layer" when the map holds a surface nearer the light in its direction. One layer
// cannot say what lies behind it; two rules decide whether the ray hit something there:
//  * thickness: a point behind the layer by less than `thickness` x the layer's depth is inside
//    the occluder (the screen-space ray marcher's rule);
//  * EXTRAPOLATE (the engines' occluder extrapolation): a ray that comes out from behind the
//    layer hit the occluder it was behind when, at its first point in front of the layer, it is
//    nearer the light than that occluder's depth extrapolated to the point with depth slope
//    `slope` (per unit of lateral distance): it crossed the occluder's surface, or the surface's
//    continuation past the silhouette it came out from under. A thin occluder (a plate) then
//    needs no thickness and no step landing inside it.
// What no rule can know: a second occluder hidden behind the first from the light centre, which
// rays towards the light's border pass through (the engines' "inconsistent penumbra" where
// occluders overlap). `maxRayAngle` (radians, as seen from the light centre; 0: none) ends each
// ray where it has spanned that angle: the rest of the ray is taken as unoccluded.
#include "single_view_bindings.h"
#include "pcss_common.glsl"

uniform int rays;
uniform int steps;
uniform float spacing;  // step s at t = ((s + offset) / steps)^spacing: 1 even, > 1 denser near the receiver
uniform float thickness;
uniform float slope;
uniform float maxRayAngle;
uniform int jitter;  // 0: fixed offsets; 1: per-pixel interleaved gradient noise (sample rotation, step offset)

out vec4 outVisibility;

// The angle between the directions from the light centre to a and b; 0 where either is the
// centre itself (a point light's sample, or a ray's end on it), never NaN.
float angleFromLight(vec3 a, vec3 b) {
  vec3 u = a - lightPosition, v = b - lightPosition;
  float s = length(cross(u, v)), c = dot(u, v);
  return s == 0.0 && c == 0.0 ? 0.0 : atan(s, c);
}

// 1 where the ray from the receiver r to the light point q reaches it through the map, else 0.
// The receiver's plane is not an occluder (the receiver-plane depth of pcss_common.glsl): a layer
// at or behind that plane along a step's direction, less the receiver's bias, is taken as empty,
// so a planar or convex receiver does not shadow itself through the map's texels.
float traceRay(Receiver r, vec3 q, float offset) {
  vec3 o = r.o;
  float tEnd = 1.0;
  if (maxRayAngle > 0.0) {
    // The ray's angular span seen from the centre grows with t; bisect for the end.
    if (angleFromLight(o, q) > maxRayAngle) {
      float lo = 0.0, hi = 1.0;
      for (int i = 0; i < 20; ++i) {
        float mid = 0.5 * (lo + hi);
        if (angleFromLight(o, mix(o, q, mid)) > maxRayAngle) hi = mid; else lo = mid;
      }
      tEnd = lo;
    }
  }
  bool wasBehind = false;
  float occluder = 0.0;  // view depth of the layer the ray was last behind
  vec2 occluderUv = vec2(0.0);
  for (int s = 0; s < steps; ++s) {
    vec3 x = mix(o, q, tEnd * pow((float(s) + offset) / float(steps), spacing));
    vec4 c = mapClip(x, lightPosition);
    if (c.w <= mapNear) break;  // at the light's near plane: the map holds nothing nearer
    vec2 uv = mapUv(c.xy / c.w);
    float z = texture(depthRaw, uv).r;  // reversed depth; 0: nothing (or outside the map)
    float layer = z > 0.0 ? mapNear / z : 3.0e38;
    float margin = r.bias * c.w / r.d;
    if (layer >= planeDepth(r.o, r.n, lightPosition, c.xy / c.w, r.d) - r.bias) layer = 3.0e38;
    bool behind = c.w > layer + margin;
    if (behind && c.w < layer * (1.0 + thickness)) return 0.0;
#ifdef EXTRAPOLATE
    if (wasBehind && !behind) {
      float lateral = length(uv - occluderUv) * worldPerUv(occluder);
      if (c.w < occluder + slope * lateral) return 0.0;
    }
#endif
    if (behind) {
      occluder = layer;
      occluderUv = uv;
    }
    wasBehind = behind;
  }
  return 1.0;
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec3 p, n;
  if (texelFetch(gPosition, px, 0).w == 0.0) { outVisibility = vec4(0.0); return; }
  Receiver r = receiverOf(px, p, n);
  uint base = pixelSampleBase(px);
  int count = int(sampleCount);
  int traced = raysTraced(rays, count);
  float noise = jitter != 0 ? interleavedGradientNoise(vec2(px) + 0.5) : 0.0;
  float offset = jitter != 0 ? fract(noise * 7.0 + 0.5) : 0.5;
  int first = int(noise * float(count));
  // The rays' samples (light_rays.glsl); the estimate is the ratio form: the pixel's mean
  // luminance over all its samples above the horizon (as pcss's), times the share of the traced
  // rays' luminance that arrives, so that a lit or a fully shadowed pixel is exact whatever the
  // subset (a textured light's samples differ a lot; their subset's own mean would be noise).
  vec3 total = vec3(0.0), lit = vec3(0.0);
  for (int i = 0; i < traced; ++i) {
    uint k = raySample(i, traced, count, first);
    vec3 q = samplePositions[base + k].xyz;
    if (!aboveHorizon(p, n, q)) continue;
    vec3 l = sampleLuminance[base + k].rgb;
    total += l;
    lit += l * (r.inView ? traceRay(r, q, offset) : 1.0);
  }
  outVisibility = vec4(horizonLuminance(px, p, n) * arrivingShare(lit, total), 1.0);
}
