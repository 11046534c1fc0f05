// vssm shadow pass (src/techniques/vssm): variance soft shadow mapping (Yang et al. 2010) on the
// summed-area table of vssm_sat.comp, in the PCSS framework of pcss_common.glsl.
//  1. Blocker search over the same region as pcss, split into blockerDiv x blockerDiv sub-kernels
//     (uniform subdivision, section 5.2). A sub-kernel whose mean depth is below the receiver's
//     is "normal": its moments join the normal group, whose average blocker depth is eq. 4 with
//     z_unocc = t and P(x >= t) from Chebyshev (eq. 1). One whose mean is not below is a
//     "non-planarity" sub-kernel: fully lit if its variance is below `threshold`, else 2 x 2
//     point samples decide (section 5.1, option 2).
//  2. Penumbra by parallel planes (as pcss).
//  3. Visibility over the penumbra kernel split into shadowDiv x shadowDiv sub-kernels the same
//     way: Chebyshev's bound for the normal group, 1 for lit sub-kernels, 2 x 2 samples for the
//     rest, weighted by area (Algorithm 2, L29-L32).
// Where we diverge (for now): no min-max hierarchical shadow map, no adaptive quad-tree, no
// contact-shadow fallback (issue 6 continues).
#include "pcss_common.glsl"
#ifdef EXACT
#define SAT_T dvec2
#define SAT_SCALE double(PENUMBRA_VSSM_FIXED_ONE)
#else
#define SAT_T vec2
#define SAT_SCALE 1.0
#endif
layout(std430, binding = PENUMBRA_SSBO_VSSM_SAT) readonly buffer Sat { SAT_T sat[]; };
uniform float depthMin, depthMax;
uniform int blockerDiv;
uniform int shadowDiv;
uniform float threshold;  // variance (normalised depth^2) below which a sub-kernel is flat

out vec4 outVisibility;

SAT_T satAt(int x, int y) { return (x < 0 || y < 0) ? SAT_T(0) : sat[y * mapSize + x]; }

// Moments (mean x, mean x^2) and texel count of the inclusive box [lo, hi].
struct Box {
  float mean, meanSq, area;
};
Box boxMoments(ivec2 lo, ivec2 hi) {
  SAT_T s = satAt(hi.x, hi.y) - satAt(lo.x - 1, hi.y) - satAt(hi.x, lo.y - 1) + satAt(lo.x - 1, lo.y - 1);
  Box b;
  b.area = float((hi.x - lo.x + 1) * (hi.y - lo.y + 1));
  b.mean = float(s.x / (SAT_SCALE * double(b.area)));
  b.meanSq = float(s.y / (SAT_SCALE * SAT_SCALE * double(b.area)));
  return b;
}

float normalisedDepth(float d) { return clamp((d - depthMin) / (depthMax - depthMin), 0.0, 1.0); }
float viewDepth(float x) { return depthMin + x * (depthMax - depthMin); }

// Chebyshev's one-tailed bound (eq. 1): P(x >= t) for mean mu < t, variance var.
float chebyshev(float mu, float var, float t) {
  var = max(var, 1e-12);
  return var / (var + (t - mu) * (t - mu));
}

// Over the texel box of the kernel around uv of half-size radius (uv), split div x div:
// returns (lit area, blocked area, blocker depth sum weighted by blocked area, total area).
vec4 kernel(Receiver r, float t, float radius, int div) {
  vec2 c = r.uv * float(mapSize);
  float extent = max(radius * float(mapSize), 0.5);
  ivec2 lo = clamp(ivec2(floor(c - extent)), ivec2(0), ivec2(mapSize - 1));
  ivec2 hi = clamp(ivec2(floor(c + extent)), ivec2(0), ivec2(mapSize - 1));
  ivec2 span = hi - lo + 1;
  float normalSum = 0.0, normalSq = 0.0, normalArea = 0.0;
  float lit = 0.0, blocked = 0.0, blockerSum = 0.0, total = 0.0;
  for (int j = 0; j < div; ++j)
    for (int i = 0; i < div; ++i) {
      ivec2 a = lo + (span * ivec2(i, j)) / div;
      ivec2 b = lo + (span * ivec2(i + 1, j + 1)) / div - 1;
      if (any(lessThan(b, a))) continue;
      Box box = boxMoments(a, b);
      total += box.area;
      if (box.mean < t) {
        normalSum += box.mean * box.area;
        normalSq += box.meanSq * box.area;
        normalArea += box.area;
      } else if (box.meanSq - box.mean * box.mean < threshold) {
        lit += box.area;
      } else {
        // 2 x 2 point samples at the sub-kernel's quarter points.
        float hits = 0.0, depthSum = 0.0;
        for (int s = 0; s < 4; ++s) {
          vec2 f = vec2(float(s & 1) * 0.5 + 0.25, float(s >> 1) * 0.5 + 0.25);
          ivec2 q = a + ivec2(vec2(b - a + 1) * f);
          float z = texelFetch(depthRaw, q, 0).r;
          float x = z > 0.0 ? normalisedDepth(mapNear / z) : 1.0;
          if (x < t) { hits += 1.0; depthSum += x; }
        }
        lit += box.area * (4.0 - hits) / 4.0;
        blocked += box.area * hits / 4.0;
        blockerSum += hits > 0.0 ? box.area * depthSum / 4.0 : 0.0;
      }
    }
  if (normalArea > 0.0) {
    float mu = normalSum / normalArea, var = normalSq / normalArea - mu * mu;
    float p = chebyshev(mu, var, t);
    lit += p * normalArea;
    // Eq. 4 with z_unocc = t: the blockers' mean depth in the normal group.
    float occluded = (1.0 - p) * normalArea;
    if (occluded > 0.0) {
      float zOcc = (mu - p * t) / max(1.0 - p, 1e-6);
      blocked += occluded;
      blockerSum += occluded * clamp(zOcc, 0.0, t);
    }
  }
  return vec4(lit, blocked, blockerSum, total);
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec3 p, n;
  if (texelFetch(gPosition, px, 0).w == 0.0) { outVisibility = vec4(0.0); return; }
  Receiver r = receiverOf(px, p, n);
  vec3 luminance = horizonLuminance(px, p, n);
  float s = 1.0;
  if (luminance != vec3(0.0) && r.inView) {
    float t = normalisedDepth(r.depth);
    vec4 search = kernel(r, t, searchRadius(r), blockerDiv);
    if (search.y > 0.0) {
      float blocker = viewDepth(search.z / search.y);
      vec4 k = kernel(r, t, penumbraRadius(r, max(blocker, mapNear)), shadowDiv);
      s = k.w > 0.0 ? k.x / k.w : 1.0;
    }
  }
  outVisibility = vec4(luminance * s, 1.0);
}
