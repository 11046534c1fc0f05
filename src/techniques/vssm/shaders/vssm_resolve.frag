// vssm shadow pass (src/techniques/vssm): variance soft shadow mapping (Yang et al. 2010) on the
// summed-area table of vssm_sat.comp, in the PCSS framework of pcss_common.glsl (Algorithm 1).
//  0. The min-max hierarchical shadow map (vssm_hsm.comp) over the blocker-search region: a
//     receiver nearer than every texel there is lit, one farther than every texel is in umbra
//     (L8-L10).
//  1. Blocker search over the same region as pcss, split into sub-kernels: a sub-kernel whose
//     mean depth is below the receiver's is "normal": its moments join the normal group, whose
//     average blocker depth is eq. 4 with z_unocc = t and P(x >= t) from Chebyshev (eq. 1, 5). One
//     whose mean is not below is a "non-planarity" sub-kernel: fully lit if its variance is below
//     `threshold` (1e-4 r), else 2 x 2 point samples decide (section 5.1, option 2).
//  2. Penumbra by parallel planes (as pcss). Contact fallback: a blocker within `contactEpsilon`
//     (0.01 r) of the receiver gives a contact shadow that the moments blur: 3 x 3 jittered PCF
//     instead.
//  3. Visibility over the penumbra kernel the same way, weighted by area (Algorithm 2, L29-L32).
// Subdivision (section 5): uniform m x m (blockerDiv / shadowDiv) or, with blockerLevels /
// shadowLevels > 0, the adaptive quad-tree of that height traversed linearly with child / next
// links (Algorithm 2; the paper's mixed default: uniform m = 5 for the blocker, H = 3 for the
// shadow).
#include "single_view_bindings.h"
#include "pcss_common.glsl"
#ifdef EXACT
#define SAT_T dvec2
#define SAT_SCALE double(PENUMBRA_VSSM_FIXED_ONE)
#else
#define SAT_T vec2
#define SAT_SCALE 1.0
#endif
layout(std430, binding = PENUMBRA_SSBO_VSSM_SAT) readonly buffer Sat { SAT_T sat[]; };
layout(std430, binding = PENUMBRA_SSBO_VSSM_HSM) readonly buffer Hsm { vec2 hsm[]; };
#include "vssm_common.glsl"
#include "moment_kernel.glsl"
uniform int blockerDiv, shadowDiv;        // uniform subdivision (when the levels are 0)
uniform int blockerLevels, shadowLevels;  // adaptive quad-tree height H (0: uniform)
uniform float threshold;       // variance (normalised depth^2) below which a sub-kernel is flat
uniform float contactEpsilon;  // view depth: blocker-receiver gap of a contact shadow
uniform int hsmLevels;

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


// Chebyshev's one-tailed bound (eq. 1): P(x >= t) for mean mu < t, variance var.
float chebyshev(float mu, float var, float t) {
  var = max(var, 1e-12);
  return var / (var + (t - mu) * (t - mu));
}

// Accumulates over the kernels' sub-kernels (Algorithm 2's areas): the normal group's moment
// sums, lit area, 2 x 2-sampled area and its blocked part and blocker depths.
struct Accum {
  float normalSum, normalSq, normalArea, normalT, lit, blocked, blockerSum, total;
};

// Classifies one sub-kernel box; returns true when it is a non-planarity box that is neither flat
// nor a leaf-level decision (the adaptive traversal then descends instead of sampling).
bool visit(inout Accum acc, Receiver r, ivec2 a, ivec2 b, bool canDescend) {
  Box box = boxMoments(a, b);
  float t = receiverAt(r, 0.5 * vec2(a + b + 1));
  if (box.mean < t) {
    acc.normalSum += box.mean * box.area;
    acc.normalSq += box.meanSq * box.area;
    acc.normalArea += box.area;
    acc.normalT += t * box.area;
  } else if (box.meanSq - box.mean * box.mean < threshold) {
    acc.lit += box.area;
  } else if (canDescend) {
    return true;
  } else {
    // 2 x 2 point samples at the sub-kernel's quarter points.
    float hits = 0.0, depthSum = 0.0;
    for (int s = 0; s < 4; ++s) {
      vec2 f = vec2(float(s & 1) * 0.5 + 0.25, float(s >> 1) * 0.5 + 0.25);
      ivec2 q = a + ivec2(vec2(b - a + 1) * f);
      float z = texelFetch(depthRaw, q, 0).r;
      float x = normalisedMapDepth(z, mapNear);
      if (x < receiverAt(r, vec2(q) + 0.5)) { hits += 1.0; depthSum += x; }
    }
    acc.lit += box.area * (4.0 - hits) / 4.0;
    acc.blocked += box.area * hits / 4.0;
    acc.blockerSum += box.area * depthSum / 4.0;
  }
  acc.total += box.area;
  return false;
}

// Returns (lit area, blocked area, blocker depth sum, total area) over the kernel.
vec4 kernel(Receiver r, float radius, int div, int levels) {
  ivec2 lo, hi;
  kernelBox(r, radius, lo, hi);
  Accum acc = Accum(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
  if (levels <= 0) {
    for (int j = 0; j < div; ++j)
      for (int i = 0; i < div; ++i) {
        ivec2 a, b;
        if (cellBox(lo, hi, div, ivec2(i, j), a, b)) visit(acc, r, a, b, false);
      }
  } else {
    // Linear quad-tree traversal (Algorithm 2): node (level, cell); child = first child one
    // level down; next = the next sibling, or the parent's next once the last child is done.
    int level = 0;
    ivec2 cell = ivec2(0);
    for (int guard = 0; guard < 4096; ++guard) {
      ivec2 a, b;
      bool descend = false;
      if (cellBox(lo, hi, 1 << level, cell, a, b)) descend = visit(acc, r, a, b, level < levels);
      if (descend) {
        ++level;
        cell *= 2;
        continue;
      }
      // next
      while (level > 0 && (cell.x & 1) == 1 && (cell.y & 1) == 1) {
        --level;
        cell /= 2;
      }
      if (level == 0) break;
      int c = (cell.y & 1) * 2 + (cell.x & 1) + 1;
      cell = (cell & ~1) + ivec2(c & 1, c >> 1);
    }
  }
  if (acc.normalArea > 0.0) {
    float mu = acc.normalSum / acc.normalArea, var = acc.normalSq / acc.normalArea - mu * mu;
    float t = acc.normalT / acc.normalArea;  // the receiver plane's mean depth over the group
    float p = chebyshev(mu, var, t);
    acc.lit += p * acc.normalArea;
    // Eq. 4 with z_unocc = t: the blockers' mean depth in the normal group.
    float occluded = (1.0 - p) * acc.normalArea;
    if (occluded > 0.0) {
      acc.blocked += occluded;
      acc.blockerSum += occluded * clamp((mu - p * t) / max(1.0 - p, 1e-6), 0.0, t);
    }
  }
  return vec4(acc.lit, acc.blocked, acc.blockerSum, acc.total);
}

// Min and max normalised depth over (a superset of) the box [lo, hi]: the HSM level at which it
// spans at most 2 x 2 texels.
vec2 hsmRange(ivec2 lo, ivec2 hi) {
  int level = 0, offset = 0;
  while (level + 1 < hsmLevels && max(hi.x - lo.x, hi.y - lo.y) >= 1) {
    offset += (mapSize >> level) * (mapSize >> level);
    ++level;
    lo /= 2;
    hi /= 2;
  }
  int size = mapSize >> level;
  vec2 range = vec2(1.0, 0.0);
  for (int y = lo.y; y <= hi.y; ++y)
    for (int x = lo.x; x <= hi.x; ++x) {
      vec2 v = hsm[offset + y * size + x];
      range = vec2(min(range.x, v.x), max(range.y, v.y));
    }
  return range;
}

// 3 x 3 jittered PCF around the receiver (the contact fallback), of half-size radius (uv).
float contactPcf(Receiver r, float radius, float phi) {
  float lit = 0.0;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) {
      vec2 jitter = 0.35 * vec2(cos(phi + float(3 * j + i)), sin(phi + float(3 * j + i)));
      vec2 uv = r.uv + radius * (vec2(i, j) + jitter);
      lit += litTap(r, uv);
    }
  return lit / 9.0;
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
    float radius = searchRadius(r);
    ivec2 lo, hi;
    kernelBox(r, radius, lo, hi);
    vec2 range = hsmRange(lo, hi);
    if (t > range.y) {
      s = 0.0;  // every texel of the region blocks: umbra
    } else if (t > range.x) {  // else lit: nothing in the region is nearer
      vec4 search = kernel(r, radius, blockerDiv, blockerLevels);
      if (search.y > 0.0) {
        float blocker = viewDepth(search.z / search.y);
        float phi = TWO_PI * interleavedGradientNoise(vec2(px) + 0.5);
        if (r.depth - blocker < contactEpsilon) {
          s = contactPcf(r, penumbraRadius(r, max(blocker, mapNear)), phi);
        } else {
          vec4 k = kernel(r, penumbraRadius(r, max(blocker, mapNear)), shadowDiv, shadowLevels);
          s = k.w > 0.0 ? k.x / k.w : 1.0;
        }
      }
    }
  }
  outVisibility = vec4(luminance * s, 1.0);
}
