// The shading math both languages compute alike: the unshadowed term of the ratio estimator,
// rect and disk lights as polygons, a light sample's geometric term, the BRDF, the LTC
// integral, textured lights' prefiltered emission. The pipeline's shaders and the CPU
// reference (src/reference, src/shading) call these very functions. Valid in C++ and GLSL
// (shared/shared.h); C++ includes it through shading/shading_shared.hpp.
#ifndef PENUMBRA_SHADING_H
#define PENUMBRA_SHADING_H

#include "shared/shared.h"

// ---- the unshadowed term of the ratio estimator ----------------------
// atan2(y, x) for y >= 0, in [0, pi], to about 1e-7 relative: Cephes' atanf (S. Moshier), its
// range reduction by tan(pi/8) and tan(3 pi/8) and its polynomial. GLSL only asks atan for an
// absolute error of about 2^-11 and llvmpipe's gave the polygon formula 3e-4 relative errors
// where a far light's edge terms cancel; this one is the same on the CPU and every GL.
PENUMBRA_FN float penumbraAtan2(float y, float x) {
  float ax = abs(x);
  float base = 0.0f;
  float r = 0.0f;
  if (y > 2.414213562f * ax) {
    base = 1.5707963268f;
    r = -ax / y;
  } else if (y > 0.414213562f * ax) {
    base = 0.7853981634f;
    r = (y - ax) / (y + ax);
  } else if (ax > 0.0f) {
    r = y / ax;
  }
  float z = r * r;
  float a = base + ((((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) * z * r + r);
  return x < 0.0f ? 3.1415926536f - a : a;
}

// ---- rect and disk lights as polygons seen from a point ------------------------------------
// Lambert's formula (Lambert 1760; in vector form Arvo 1995, "Applications of irradiance tensors
// to the simulation of non-Lambertian phenomena", eq. 8): for a polygon in z's hemisphere, the
// integral over its solid angle of the cosine with the unit z is 1/2 |sum_i E(v_i, v_i+1)|,
// E(u, v) = Theta (gamma . z) with Theta the angle between u and v and gamma the unit normal of
// the plane through the origin and that edge. Angles by atan2 (acos loses small ones). E is
// scale-invariant in each vertex (no normalize: an approximate inverse square root would cost
// more than the cancellation between the edges of a far polygon already does).
// The edge from u to u + e: its cross product as u x e, exact where e is (the light's edge
// vectors are made directly, not as differences of nearly equal vertices far from the light).
PENUMBRA_FN float penumbraEdgeIntegral(vec3 u, vec3 e, vec3 z) {
  vec3 c = cross(u, e);
  float s = length(c);
  return s > 0.0f ? penumbraAtan2(s, dot(u, u) + dot(u, e)) * (dot(c, z) / s) : 0.0f;
}

// The LTC frame's x: v's part orthogonal to ns (v along ns: the lobe is isotropic about ns, the
// t = 0 cells, any tangent serves); y = ns x x, z = ns.
PENUMBRA_FN vec3 penumbraLtcTangent(vec3 ns, vec3 v) {
  vec3 x = v - ns * dot(v, ns);
  if (!(length(x) > 1e-6f)) x = abs(ns.x) < 0.9f ? cross(ns, vec3(1.0f, 0.0f, 0.0f)) : cross(ns, vec3(0.0f, 1.0f, 0.0f));
  return normalize(x);
}

// w in the LTC frame (x, y, z), mapped by M^-1 = (a, c, b, d) (the LTC section below).
PENUMBRA_FN vec3 penumbraLtcMap(vec3 w, vec3 x, vec3 y, vec3 z, vec4 minv) {
  vec3 t = vec3(dot(w, x), dot(w, y), dot(w, z));
  return vec3(minv.x * t.x + minv.z * t.z, t.y, minv.y * t.x + minv.w * t.z);
}

// The light's polygon is clipped to half-spaces dot(plane_k, x) > 0 through the point, in order:
// 0 the geometric normal ng (the horizon rule every technique and the reference apply per sample,
// docs/architecture.md "Conventions"), 1 the shading normal ns (the cosine's max(., 0)), and for the LTC 2 the
// plane the transform maps to z = 0 (D_o's support). Clipping is streamed edge by edge (no vertex
// arrays, whose dynamic indexing made llvmpipe compile the shading shader for 80 s): an edge is
// cut by each plane in turn; where it leaves plane k's half-space the cut point is the clipped
// polygon's exit point on plane k, where it enters its entry point; once every edge is through,
// each plane's closing edge (exit -> entry, on the plane: the clipped polygon is convex, so one of
// each) is cut by the planes after it. Lambert's sum with z = ns takes the edges past planes 0-1,
// the LTC's (the edges mapped by M^-1 in the frame (x, y, ns), z = its z) those past plane 2.
struct PenumbraPolygonClip {
  vec3 plane[3];
  vec3 exitPoint[3];
  vec3 entryPoint[3];
  int crossings[3];  // bit 0: an exit point, bit 1: an entry point
  vec3 x, y;         // the LTC frame's tangents (z = plane[1] = ns)
  vec4 minv;         // (a, c, b, d) of M^-1 (the LTC section below)
  float lambert, ltc;
  int planes;        // 2: Lambert only, 3: also the LTC
};

// Edge (u, v) of the boundary (relative to the point) through planes first..planes-1; e = v - u,
// exact where it can be (penumbraEdgeIntegral). Each end is classified by dot(plane, end) of that
// very vector, the same value for the edges that share it (u + e would round differently: a cut
// point on plane 0 read as inside plane 1 at one edge's end and outside at the next edge's start
// lost the closing edge when ng = ns).
PENUMBRA_FN void penumbraClipEdge(PENUMBRA_INOUT(PenumbraPolygonClip) c, vec3 u, vec3 v, vec3 e, int first) {
  for (int k = 0; k < 3; ++k) {
    if (k == 2 && first <= 2) {
      c.lambert += penumbraEdgeIntegral(u, e, c.plane[1]);
      if (c.planes == 2) return;
    }
    if (k < first) continue;
    float hu = dot(c.plane[k], u), hv = dot(c.plane[k], v);
    if (!(hu > 0.0f) && !(hv > 0.0f)) return;
    if ((hu > 0.0f) != (hv > 0.0f)) {
      float t = hu / (hu - hv);
      vec3 cut = u + e * t;
      if (hu > 0.0f) {
        c.exitPoint[k] = cut;
        c.crossings[k] |= 1;
        v = cut;
        e = e * t;
      } else {
        c.entryPoint[k] = cut;
        c.crossings[k] |= 2;
        u = cut;
        e = e * (1.0f - t);
      }
    }
  }
  c.ltc += penumbraEdgeIntegral(penumbraLtcMap(u, c.x, c.y, c.plane[1], c.minv),
                                penumbraLtcMap(e, c.x, c.y, c.plane[1], c.minv), vec3(0.0f, 0.0f, 1.0f));
}

// A rect light (PENUMBRA_LIGHT_RECT: centre, unit tangent and bitangent, half extents `size`) or
// a disk light (PENUMBRA_LIGHT_DISK: radius size.x) seen from p, with geometric and shading
// normals ng and ns: (x) the irradiance of the light at radiance 1, the integral over it of
// cos(theta_p) cos(theta_l) / r^2 dA (m^2 / m^2: a form factor times pi), and, when withLtc, (y)
// the integral over it of the normalised LTC lobe for the view v and the table's M^-1 `minv`
// (the LTC section below). The disk is its equal-area regular 32-gon (radius scaled by
// sqrt((2 pi / 32) / sin(2 pi / 32)), so the polygon's area is the disk's): a disk has no
// elementary closed form off its axis (its vector irradiance is that of a circular current loop,
// elliptic integrals) and none once clipped; through Lambert's formula the 32-gon is within 3e-6
// relative of the disk while it is wholly above the horizon, 1.4e-4 where the horizon cuts it
// (tests/raytrace_analytic.cpp). The corners by rotating one (a rect's by
// pi / 2, the disk's by 2 pi / 32: no GL cos and sin). The emitter's one-sidedness is the
// caller's (a point behind the light's plane sees none of it).
PENUMBRA_FN vec2 penumbraLightPolygon(int shape, vec3 p, vec3 ng, vec3 ns, vec3 centre, vec3 tangent, vec3 bitangent,
                                      vec2 size, bool withLtc, vec3 v, vec4 minv) {
  PenumbraPolygonClip c;
  c.plane[0] = ng;
  c.plane[1] = ns;
  for (int k = 0; k < 3; ++k) {
    c.crossings[k] = 0;
    c.exitPoint[k] = vec3(0.0f);
    c.entryPoint[k] = vec3(0.0f);
  }
  c.lambert = 0.0f;
  c.ltc = 0.0f;
  c.planes = withLtc ? 3 : 2;
  c.minv = minv;
  // Plane 2: (M^-1 w).z > 0, i.e. w . (c x + d ns) > 0.
  c.x = penumbraLtcTangent(ns, v);
  c.y = cross(ns, c.x);
  c.plane[2] = c.x * minv.y + ns * minv.w;

  bool disk = shape == PENUMBRA_LIGHT_DISK;
  int n = disk ? 32 : 4;
  vec2 scale = disk ? vec2(size.x * 1.003222080f) : size;  // sqrt((pi / 16) / sin(pi / 16))
  vec2 rotation = disk ? vec2(0.980785280f, 0.195090322f) : vec2(0.0f, 1.0f);  // cos, sin of the step
  vec2 corner = disk ? vec2(1.0f, 0.0f) : vec2(-1.0f, -1.0f);
  vec3 base = centre - p;
  vec2 firstCorner = corner;
  vec3 first = base + tangent * (corner.x * scale.x) + bitangent * (corner.y * scale.y);
  vec3 u = first;
  for (int i = 0; i < n; ++i) {
    vec2 next = i == n - 1 ? firstCorner
                           : vec2(corner.x * rotation.x - corner.y * rotation.y, corner.y * rotation.x + corner.x * rotation.y);
    vec3 v = i == n - 1 ? first : base + tangent * (next.x * scale.x) + bitangent * (next.y * scale.y);
    vec3 e = tangent * ((next.x - corner.x) * scale.x) + bitangent * ((next.y - corner.y) * scale.y);
    penumbraClipEdge(c, u, v, e, 0);
    u = v;
    corner = next;
  }
  for (int k = 0; k < 3; ++k)
    if (c.crossings[k] == 3)
      penumbraClipEdge(c, c.exitPoint[k], c.entryPoint[k], c.entryPoint[k] - c.exitPoint[k], k + 1);
  return vec2(0.5f * abs(c.lambert), 0.5f * 0.31830988618f * abs(c.ltc));
}

PENUMBRA_FN float penumbraRectIrradiance(vec3 p, vec3 ng, vec3 ns, vec3 centre, vec3 tangent, vec3 bitangent,
                                         vec2 halfSize) {
  return penumbraLightPolygon(PENUMBRA_LIGHT_RECT, p, ng, ns, centre, tangent, bitangent, halfSize, false, ns,
                              vec4(1.0f, 0.0f, 0.0f, 1.0f)).x;
}

PENUMBRA_FN float penumbraDiskIrradiance(vec3 p, vec3 ng, vec3 ns, vec3 centre, vec3 tangent, vec3 bitangent,
                                         float radius) {
  return penumbraLightPolygon(PENUMBRA_LIGHT_DISK, p, ng, ns, centre, tangent, bitangent, vec2(radius), false, ns,
                              vec4(1.0f, 0.0f, 0.0f, 1.0f)).x;
}

// The cosine-weighted solid angle of a spherical cap of angular radius alpha (sin^2 alpha =
// sin2Alpha) whose axis makes the angle beta with the normal, clipped to the normal's hemisphere:
// pi sin^2(alpha) cos(beta) while the cap is wholly above the horizon, else Snyder's closed form
// for the cap crossing the horizon (J. Snyder 1996, "Area light sources for real-time graphics",
// MSR-TR-96-11; as in Lagarde and de Rousiers 2014, "Moving Frostbite to PBR", section 4.7.2):
// x = cot(alpha), y = -x cot(beta),
//   F = (cos(beta) acos(y) - x sin(beta) sqrt(1 - y^2)) sin^2(alpha) + atan(sin(beta) sqrt(1 - y^2) / x).
// Angles by penumbraAtan2 (GLSL's acos and atan are too coarse). Within 3.6e-6 of a 400 x 400
// quadrature over the cap (ClosedForms.CapCosineIsTheClippedIntegral).
PENUMBRA_FN float penumbraCapCosine(float cosBeta, float sin2Alpha) {
  if (cosBeta * cosBeta > sin2Alpha) return cosBeta > 0.0f ? 3.1415926536f * sin2Alpha * cosBeta : 0.0f;
  float sinBeta = sqrt(max(1.0f - cosBeta * cosBeta, 0.0f));
  float x = sqrt(max(1.0f / sin2Alpha - 1.0f, 0.0f));
  float y = sinBeta > 0.0f ? clamp(-x * cosBeta / sinBeta, -1.0f, 1.0f) : 0.0f;
  float sy = sqrt(max(1.0f - y * y, 0.0f));
  float acosY = penumbraAtan2(sy, y);
  float f = (cosBeta * acosY - x * sinBeta * sy) * sin2Alpha + penumbraAtan2(sinBeta * sy, x);
  return max(f, 0.0f);
}

// The same integral for a sphere light as penumbra models it (docs/architecture.md "Lighting pipeline": a
// ball of isotropic points, sampled in its volume, of total intensity L pi R^2). While the ball
// lies wholly above both the geometric and the shading normal's planes through p, the cosines
// need no clamping and the integral is the normal component of an inverse-square field, which
// for a uniform ball is that of its centre (Newton's shell theorem): pi R^2 cos(theta_s) / d^2.
// That is also the irradiance of a Lambertian sphere of radiance L seen fully above the horizon.
// Where the ball crosses the horizon, it is cut into shells about p: the
// shell of radius r meets the ball in a cap of angular radius alpha(r), cos(alpha) =
// (d^2 + r^2 - R^2) / (2 d r), and contributes the cap's clipped cosine integral
// (penumbraCapCosine) times the ball's intensity per volume, 3 / (4 R) of L: a 1D integral over
// r in [d - R, d + R], taken with r = d - R cos(t) by the midpoint rule in t on 32 points
// (spectrally accurate for this smooth integrand: in double 5e-6 relative at d >= 1.1 R, 2.4e-4
// at d = 1.001 R, against 20000 points; 1.7e-5 in float, tests/raytrace_analytic.cpp). One
// plane clips it: the shading normal's, when the ball is wholly above the geometric one's or the
// two normals agree (|ng - ns| <= 1e-5: a flat surface's interpolated normal). Returns -1
// otherwise, and for p inside the ball (the caller sums the samples).
PENUMBRA_FN float penumbraBallIrradiance(vec3 p, vec3 ng, vec3 ns, vec3 centre, float radius) {
  vec3 d = centre - p;
  float aboveS = dot(ns, d), aboveG = dot(ng, d);
  float d2 = dot(d, d);
  float dist = sqrt(d2);
  if (aboveS > radius && aboveG > radius) return 3.1415926536f * radius * radius * aboveS / (d2 * dist);
  if (!(dist > radius)) return -1.0f;
  if (!(aboveG > radius) && !(length(ng - ns) <= 1e-5f)) return -1.0f;
  float cosBeta = aboveS / dist;
  float sum = 0.0f;
  // cos(t) and sin(t) at t = (i + 1/2) pi / 32 by rotating by pi / 32 (no GL's cos and sin,
  // whose precision differs between drivers: the same numbers on the CPU and every GL).
  float c = 0.998795456f, sn = 0.049067674f;
  for (int i = 0; i < 32; ++i) {
    // 1 - cos(alpha) = (R^2 - (d - r)^2) / (2 d r) = R^2 sin^2(t) / (2 d r), as d - r = R cos(t):
    // sin^2(alpha) = u (2 - u) without the cancellation of 1 - cos^2(alpha) near the ends.
    float r = dist - radius * c;
    float u = radius * radius * sn * sn / (2.0f * dist * r);
    float sin2Alpha = min(u * (2.0f - u), 1.0f);
    if (sin2Alpha > 0.0f) sum += sn * penumbraCapCosine(cosBeta, sin2Alpha);
    float next = c * 0.995184727f - sn * 0.098017140f;
    sn = sn * 0.995184727f + c * 0.098017140f;
    c = next;
  }
  // 3 / (4 R) * R sin(t) dt summed with dt = pi / 32.
  return sum * (3.0f * 3.1415926536f / 128.0f);
}

// ---- a light sample's geometric term -----------------------------------------------------
// cos(theta_s) [cos(theta_l)] / r^2 of the light point x seen from p: 0 below the geometric
// normal ng's horizon (the horizon rule, docs/architecture.md "Conventions"), the cosine with the shading
// normal ns clamped at 0, [cos(theta_l)] only for a one-sided emitter (lightNormal its emission
// normal; 0 for isotropic lights, LightSampleSet::lightNormal). The pipeline's shading and the
// reference's shaded image both weight each sample by it.
PENUMBRA_FN float penumbraSampleGeometry(vec3 p, vec3 ng, vec3 ns, vec3 x, vec3 lightNormal) {
  vec3 d = x - p;
  if (!(dot(ng, d) > 0.0f)) return 0.0f;
  float r2 = dot(d, d);
  vec3 l = d / sqrt(r2);
  float emitter = dot(lightNormal, lightNormal) > 0.0f ? max(-dot(lightNormal, l), 0.0f) : 1.0f;
  return max(dot(ns, l), 0.0f) * emitter / r2;
}

// ---- BRDF -------------------------------------------------------------
// LAMBERT: albedo / pi (scene-file materials without "metallic"/"roughness", OBJ without Ks).
// METALLIC_ROUGHNESS: the glTF 2.0 specification's BRDF (Appendix B, "BRDF Implementation"):
//   c_diff = mix(baseColor, 0, metallic), f0 = mix(0.04, baseColor, metallic), alpha = roughness^2,
//   F = f0 + (1 - f0) (1 - |v.h|)^5 (Schlick), f = (1 - F) c_diff / pi + F D V,
//   D the GGX (Trowbridge-Reitz) distribution, V = G / (4 |n.l| |n.v|) with G the separable
//   Smith-GGX masking-shadowing (spec eq. for V_GGX).
// Divergence: roughness is clamped to >= PENUMBRA_MIN_ROUGHNESS (a mirror's D is a delta no
// light sample can hit; Filament clamps at the same value), and n.v to >= 1e-4 (a shading normal
// turned from the viewer: the lobe's limit, not a division by zero).
#define PENUMBRA_MIN_ROUGHNESS 0.045f

// GGX D(h) for alpha^2 = a2, nh = n.h (> 0).
PENUMBRA_FN float penumbraGgxD(float nh, float a2) {
  float d = nh * nh * (a2 - 1.0f) + 1.0f;
  return a2 / (3.1415926536f * d * d);
}

// The visibility term V = G / (4 n.l n.v) of the separable Smith-GGX G (glTF 2.0 Appendix B).
PENUMBRA_FN float penumbraGgxVisibility(float nl, float nv, float a2) {
  return 1.0f / ((nl + sqrt(a2 + (1.0f - a2) * nl * nl)) * (nv + sqrt(a2 + (1.0f - a2) * nv * nv)));
}

// The specular lobe without Fresnel, times the cosine: D V (n.l), for unit n, v, l. 0 below
// the horizon of n. What the LTC table fits (Heitz et al. 2016, section 4: BRDF * cos with F = 1).
PENUMBRA_FN float penumbraGgxCosine(vec3 n, vec3 v, vec3 l, float alpha) {
  float nl = dot(n, l);
  if (!(nl > 0.0f)) return 0.0f;
  float nv = max(dot(n, v), 1e-4f);
  vec3 h = v + l;
  float hl = length(h);
  if (!(hl > 0.0f)) return 0.0f;
  float nh = dot(n, h) / hl;
  if (!(nh > 0.0f)) return 0.0f;
  float a2 = alpha * alpha;
  return penumbraGgxD(nh, a2) * penumbraGgxVisibility(nl, nv, a2) * nl;
}

PENUMBRA_FN float penumbraAlpha(float roughness) {
  float r = max(roughness, PENUMBRA_MIN_ROUGHNESS);
  return r * r;
}

// Schlick's Fresnel for f0 at v.h.
PENUMBRA_FN vec3 penumbraSchlick(vec3 f0, float vh) {
  float m = 1.0f - max(vh, 0.0f);
  float m5 = m * m * m * m * m;
  return f0 + (vec3(1.0f) - f0) * m5;
}

// The BRDF f(v, l) = diffuse + specular (1/sr, rgb; the cosine not included) with shading
// normal n, unit v towards the viewer and l towards the light, in two parts: the ratio
// estimator gives each its own unshadowed term (Lambert's formula, LTC). Below n's horizon the
// specular part is 0 and the diffuse part keeps its value (the callers' cosine, clamped at 0,
// removes it).
PENUMBRA_FN vec3 penumbraF0(vec3 baseColor, float metallic) {
  return vec3(0.04f) * (1.0f - metallic) + baseColor * metallic;
}

PENUMBRA_FN vec3 penumbraFresnel(vec3 v, vec3 l, vec3 baseColor, float metallic) {
  vec3 f0 = penumbraF0(baseColor, metallic);
  vec3 h = v + l;
  float hl = length(h);
  return penumbraSchlick(f0, hl > 0.0f ? dot(v, h) / hl : 0.0f);
}

PENUMBRA_FN vec3 penumbraBrdfDiffuse(vec3 v, vec3 l, vec3 baseColor, float metallic, int model) {
  if (model != PENUMBRA_BRDF_METALLIC_ROUGHNESS) return baseColor * 0.31830988618f;
  return (vec3(1.0f) - penumbraFresnel(v, l, baseColor, metallic)) * baseColor * ((1.0f - metallic) * 0.31830988618f);
}

PENUMBRA_FN vec3 penumbraBrdfSpecular(vec3 n, vec3 v, vec3 l, vec3 baseColor, float metallic, float roughness,
                                      int model) {
  float nl = dot(n, l);
  if (model != PENUMBRA_BRDF_METALLIC_ROUGHNESS || !(nl > 0.0f)) return vec3(0.0f);
  return penumbraFresnel(v, l, baseColor, metallic) * (penumbraGgxCosine(n, v, l, penumbraAlpha(roughness)) / nl);
}

PENUMBRA_FN vec3 penumbraBrdf(vec3 n, vec3 v, vec3 l, vec3 baseColor, float metallic, float roughness, int model) {
  return penumbraBrdfDiffuse(v, l, baseColor, metallic, model) +
         penumbraBrdfSpecular(n, v, l, baseColor, metallic, roughness, model);
}


// ---- the GGX lobe's unshadowed integral over a polygon (LTC) --------------------------------
// Heitz, Dupuy, Hill and Neubelt 2016, "Real-time polygonal-light shading with linearly
// transformed cosines", section 5: the integral over a polygon of the lobe penumbraGgxCosine (F =
// 1) is norm times that of the clamped cosine D_o over the polygon transformed by M^-1, which is
// Lambert's formula / pi (penumbraLightPolygon's y). minv holds the table's (a, c, b, d) of
// M^-1 = [[a 0 b] [0 1 0] [c 0 d]] (src/shading/ltc.h) in the frame x = v's part orthogonal to
// ns, y = ns x x, z = ns. Divergence: the polygon is first clipped to the horizons of ng (the
// horizon rule) and of ns (the true lobe is 0 below it; the paper clips only the transformed
// polygon at z = 0, which we also do: D_o's support). Clipping commutes with the linear map, so
// the world planes clip before it. The caller multiplies by norm, Schlick's Fresnel at
// penumbraLtcFresnelDirection and the radiance.

// The table's texture coordinates (ltc.h grid: roughness, sqrt(1 - cos theta_v)) for a table of
// `size` cells a side, at texel centres.
PENUMBRA_FN vec2 penumbraLtcCoordinates(float roughness, float nv, float size) {
  vec2 g = vec2(clamp(roughness, 0.0f, 1.0f), sqrt(max(1.0f - clamp(nv, 0.0f, 1.0f), 0.0f)));
  return (g * (size - 1.0f) + vec2(0.5f)) / size;
}


// The direction at which the LTC's specular integral takes Schlick's Fresnel factor: towards the
// light's point nearest the mirror ray's hit on its plane (a rect's clamped to its extents, a
// disk's radially), moved towards the light's centre by min(2 alpha, 1) (the centre where the
// mirror ray does not meet the plane in front of p). Divergence from the paper's split (Hill
// 2016: norm and fresnel, the lobe's Schlick-weighted integral over the whole hemisphere, so
// F = f0 (norm - fresnel) + fresnel): at grazing views the hemisphere's average is the Fresnel of
// the lobe's grazing peak, not of the light's part of it, and a dielectric's specular term was
// 20-46% too high at roughness 0.3-0.7 (tests/shading_ltc_test.cpp; this: 2.5-6%, and 0.3% at
// roughness 0.05-0.1). A representative point as in Karis 2013 (section "Area lights"), with
// its distance to the centre our own heuristic, measured only on that test's floor.
PENUMBRA_FN vec3 penumbraLtcFresnelDirection(int shape, vec3 p, vec3 ns, vec3 v, vec3 centre, vec3 lightNormal,
                                             vec3 tangent, vec3 bitangent, vec2 size, float alpha) {
  vec3 m = ns * (2.0f * dot(ns, v)) - v;
  float towards = dot(m, lightNormal);
  vec3 q = centre;
  if (towards < -1e-4f) {  // unit vectors: the hit is at most 1e4 times p's distance to the plane
    vec3 hit = p + m * (dot(centre - p, lightNormal) / towards) - centre;
    vec2 uv = vec2(dot(hit, tangent), dot(hit, bitangent));
    if (shape == PENUMBRA_LIGHT_DISK) {
      float r = length(uv);
      if (r > size.x) uv = uv * (size.x / r);
    } else {
      uv = clamp(uv, -size, size);
    }
    q = centre + (tangent * uv.x + bitangent * uv.y) * (1.0f - min(2.0f * alpha, 1.0f));
  }
  return normalize(q - p);
}

// ---- textured rect and disk lights (Heitz et al. 2016, section 5.3) ------------------------
// The integral of a lobe D times the emission L over the light is taken as (integral of D) times
// L_D, the emission averaged with D's weight, and L_D is read from a chain of the emission
// texture prefiltered with Gaussians of growing width (src/shading/prefiltered_light.h) at the
// orthogonal projection of the shading point onto the light's plane after the lobe's M^-1 (the
// identity for the cosine lobe), with a footprint from that point's distance to the plane over
// the square root of the mapped uv square's area (the paper's heuristics; their demo's
// FetchDiffuseFilteredTexture). Divergences: the chain is a normalised convolution restricted to
// the light (defined on the margin around it, src/shading/prefiltered_light.h); and instead of
// one level at a log of the footprint, L_D mixes every level with the weights that make the
// mixture of Gaussians the clamped cosine's own footprint on a plane facing it,
// (1 + rho^2 / d^2)^-2 (penumbraPrefilterWeight): the cosine's heavy tail, which one Gaussian
// misses (tests/shading_prefilter_test.cpp: stained glass 1.5 above a floor, 0.038 -> 0.0058
// relative RMSE of the diffuse term).
#define PENUMBRA_PREFILTER_MARGIN 0.5f  // the chain covers uv in [-margin, 1 + margin]^2

// The light's uv square (u along the tangent from centre - tangent h.x - bitangent h.y at uv 0,
// v along the bitangent; a disk's is the square about it, as its samples' uv) seen from p,
// mapped by M^-1 in the LTC frame (x, y, z): vec3(u, v) of the projection of p onto the mapped
// plane, and d = its distance to p over the square root of the mapped square's area.
PENUMBRA_FN vec3 penumbraPrefilterFootprint(vec3 p, vec3 centre, vec3 tangent, vec3 bitangent, vec2 halfSize, vec3 x,
                                            vec3 y, vec3 z, vec4 minv) {
  vec3 o = penumbraLtcMap(centre - tangent * halfSize.x - bitangent * halfSize.y - p, x, y, z, minv);
  vec3 e1 = penumbraLtcMap(tangent * (2.0f * halfSize.x), x, y, z, minv);
  vec3 e2 = penumbraLtcMap(bitangent * (2.0f * halfSize.y), x, y, z, minv);
  vec3 n = cross(e1, e2);
  float area2 = dot(n, n), h = dot(n, o);
  vec3 r = n * (h / area2) - o;  // the foot point from the corner
  float a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2), b1 = dot(r, e1), b2 = dot(r, e2);
  float det = a11 * a22 - a12 * a12;
  return vec3((b1 * a22 - b2 * a12) / det, (b2 * a11 - b1 * a12) / det, abs(h) / (sqrt(area2) * sqrt(sqrt(area2))));
}

// The share of chain level k (sigma_k = sigma0 2^k) in the cosine lobe's footprint at uv
// distance d: the lobe about the plane's normal weights the plane by (1 + rho^2 / d^2)^-2, which
// is the mixture over s of Gaussians of sigma^2 = d^2 / (2 s) with density e^-s (from
// integral_0^inf s e^(-s (1 + x)) ds = (1 + x)^-2); level k takes s in [s_k / 2, 2 s_k],
// s_k = d^2 / (2 sigma_k^2) (sigma within a factor sqrt 2 of sigma_k), level 0 all finer, the last
// level all coarser.
PENUMBRA_FN float penumbraPrefilterWeight(float d, float sigma0, int k, int levels) {
  float sigma = sigma0 * exp2(float(k));
  float s = d * d / (2.0f * sigma * sigma);
  float below = k == levels - 1 ? 1.0f : exp(-0.5f * s);  // e^-s at the bin's lower end in s (0: the coarsest level)
  float above = k == 0 ? 0.0f : exp(-2.0f * s);           // at its upper end (infinity: level 0)
  return below - above;
}

// The chain's texture coordinates of light uv.
PENUMBRA_FN vec2 penumbraPrefilterCoordinates(vec2 uv) {
  return (uv + vec2(PENUMBRA_PREFILTER_MARGIN)) / (1.0f + 2.0f * PENUMBRA_PREFILTER_MARGIN);
}

#endif
