// Depth complexity sampling (Forest, Barthe, Paulin, EG 2008), the per-fragment part shared by
// the wedge passes. Notation: p the visible point, c the light centre, s a light sample,
// e = (v0, v1) an edge, n_e = cross(v0 - p, v1 - v0) the normal of the plane through p and e
// (written with the short edge vector so that it stays accurate for edges seen end-on from p:
// the silhouette edges that matter most).
//
// D(s) = D(c) + sum over edges of dD_e(s): the depth complexity of sample s is the integration
// constant D(c) (the shadow-volume count, section 4.1) plus the changes met on the straight path
// from c to s on the light (section 4.2). The path meets edge e, as seen from p, where it crosses
// plane(p, e) at a point y such that the segment p -> y passes through e. There p enters or
// leaves the occluding frustum of each triangle t incident to e: it is inside it on the side of
// plane(p, e) where t's third vertex lies (sigma_t). So
//   dD_e(s) = sign(n_e . (s - p)) * m_e(p),  m_e(p) = sum_t w_t sigma_t,
// with w_t the weight t has in the count (shadow_volume.h): 1 for open meshes; for closed meshes
// 1 if t faces the crossing point y, which lies beyond e from p and so on the other side of t's
// plane: w_t = [n_t . (p - v0) < 0]. This is the paper's outer (+1) / inner (-1) rule, derived
// per fragment so that edges that are silhouettes for part of the light get the right sign, and
// open and non-manifold edges need no special case. Divergence from the paper: we integrate in
// 3D (segment p -> y through e) instead of projecting e onto a light plane, so sphere lights
// need nothing special and no edge is clipped against the light border.
#include "techniques/common/shadow_volume/shaders/volume_count.h"
#include "dcs_bindings.h"

struct DcsEdge {
  vec4 v0;     // xyz
  vec4 v1;     // xyz
  ivec4 meta;  // x first incidence, y incidence count, z 1 for the closed-mesh rule, w units
               // of the mesh (dcs/opacity.h: what one crossing of it adds to a count)
};
struct DcsIncidence {
  vec4 third;   // xyz: the triangle's vertex opposite the edge, w: +1 if it runs v0 -> v1, else -1
  vec4 normal;  // the triangle's plane n . x + d = 0: n (unnormalised) in its own winding, w = d
};
layout(std430, binding = PENUMBRA_SSBO_DCS_EDGES) readonly buffer DcsEdges { DcsEdge dcsEdges[]; };
layout(std430, binding = PENUMBRA_SSBO_DCS_INCIDENCES) readonly buffer DcsIncidences {
  DcsIncidence dcsIncidences[];
};

// The polytope around the light (dcs.cpp lightCorners(): a planar light's polygon in cyclic order).
uniform vec3 lightCorners[8];
uniform int lightCornerCount;  // 1 (point), 4 (a planar light's polygon) or 8 (a sphere's cube)

#ifdef DCS_PROFILE
// Where the wedge pass spends its fragments (dcs.cpp reads them into the statistics). An image,
// not a storage block: written by the geometry and the fragment stage (shared/shared.h, bindings).
layout(binding = PENUMBRA_IMAGE_DCS_PROFILE, r32ui) uniform coherent uimage2D dcsProfile;
const int profRectangleEdges = 0;  // edges drawn as their screen rectangle (dcs_wedge.geom fallback)
const int profWedgeEdges = 1;      // edges drawn as their wedge polyhedron
const int profFragments = 2;       // wedge fragments that passed the depth test on a surface (compute
                                   // path: pixels whose point is inside the solid)
const int profInPlane = 3;         // ... whose plane(p, e) crosses the light
const int profWeighted = 4;        // ... with m_e(p) != 0
const int profUpdating = 5;        // ... that change at least one counter
const int profCandidates = 6;      // compute path: (pixel, edge) pairs its tiles kept (dcs_wedge.comp)
// What one count adds: 1, or in dcs_wedge.frag the fragment's sign (a folded sliver's fragment
// counts -1, so that the counts are of (pixel, edge) pairs; uint arithmetic wraps).
uint dcsProfileStep = 1u;
#define PROFILE_COUNT(x) imageAtomicAdd(dcsProfile, ivec2(x, 0), dcsProfileStep)
#define PROFILE_ADD(x, n) imageAtomicAdd(dcsProfile, ivec2(x, 0), n)
#else
#define PROFILE_COUNT(x)
#define PROFILE_ADD(x, n)
#endif

int signOf(float x) { return x > 0.0 ? 1 : (x < 0.0 ? -1 : 0); }

// m_e(p) above. Both sigma_t and w_t depend only on the side of t's plane that p is on:
// n_e . (x_t - p) = det(v0 - p, v1 - v0, x_t - v0) = -o_t n_t . (p - v0), with x_t the third
// vertex, n_t the plane normal in t's winding and o_t = +1 when t runs v0 -> v1. That side is
// evaluated once per triangle, by one expression with the plane stored with t (n_t, d_t), so
// t's three edges agree on it when p lies (nearly) in t's plane: computed per edge, sigma_t
// and w_t disagreed between the edges of a triangle seen edge-on (dcs-silhouettes, a floor
// point 1e-6 off a sphere triangle's plane: a count of -1).
// t's term w_t sigma_t of m_e(p), from f = n_t . p + d_t (only its sign matters).
int dcsIncidenceWeight(DcsEdge e, DcsIncidence t, float f) {
  int sigma = -int(t.third.w) * signOf(f);
  int w = e.meta.z != 0 ? int(f < 0.0) : 1;
  return w * sigma;
}

int dcsEdgeWeight(DcsEdge e, vec3 p) {
  int m = 0;
  for (int k = 0; k < e.meta.y; ++k) {
    DcsIncidence t = dcsIncidences[e.meta.x + k];
    precise float f = dot(t.normal.xyz, p) + t.normal.w;
    m += dcsIncidenceWeight(e, t, f);
  }
  return m;
}

// Is m_e(p) = 0 at every point p of the box centre +- extent (the compute path's tile cull,
// dcs_wedge.comp)? m_e depends only on p's side of each incident triangle's plane, so where the
// box lies strictly on one side of every such plane, m_e is the same at all its points. The
// margin covers the rounding of f at the points (dcsEdgeWeight) and of the box: relative to the
// magnitude of the terms of f, never to the scene's size. false when a plane cuts the box.
bool dcsEdgeWeighsNothingInBox(DcsEdge e, vec3 centre, vec3 extent) {
  int m = 0;
  for (int k = 0; k < e.meta.y; ++k) {
    DcsIncidence t = dcsIncidences[e.meta.x + k];
    vec3 n = t.normal.xyz;
    float f = dot(n, centre) + t.normal.w;
    float margin = 1e-5 * (dot(abs(n), abs(centre) + extent) + abs(t.normal.w));
    if (abs(f) <= dot(abs(n), extent) + margin) return false;
    m += dcsIncidenceWeight(e, t, f);
  }
  return m == 0;
}

// Can e separate any two points of a planar light (corners x_0..x_3, grown a little, in cyclic
// order) seen from p? Only if e meets the pyramid conv(p, light), which holds every triangle
// (p, c, s): the segment is clipped against the pyramid's faces (Cyrus-Beck). A cheap,
// conservative rejection before the per-sample loop; true when p is (nearly) in the light's
// plane.
bool dcsEdgeMeetsLightPyramid(vec3 p, vec3 a, vec3 b, vec3 c, vec3 corners[4]) {
  vec3 lightN = normalize(cross(corners[1] - corners[0], corners[3] - corners[0]));
  float side = dot(lightN, p - c);
  if (abs(side) <= 1e-6 * length(p - c)) return true;
  float lo = 0.0, hi = 1.0;
  for (int j = 0; j < 5; ++j) {
    vec3 n, q;
    if (j < 4) {
      n = cross(corners[j] - p, corners[(j + 1) % 4] - p);
      if (dot(n, c - p) < 0.0) n = -n;
      q = p;
    } else {
      n = side > 0.0 ? lightN : -lightN;
      q = c;
    }
    float fa = dot(n, a - q), fb = dot(n, b - q);
    if (fa < 0.0 && fb < 0.0) return false;
    if (fa < 0.0) lo = max(lo, fa / (fa - fb));
    if (fb < 0.0) hi = min(hi, fa / (fa - fb));
  }
  return lo <= hi + 1e-4;
}

// Is sample s separated from c by e as seen from p? Exactly when the segment e = (a, b) passes
// through the triangle (p, c, s) (exact per-sample test; the edge LUT of section 7.3 comes
// later): a and b lie on opposite sides of the triangle's plane, and the line a -> b passes the
// triangle's three sides on the same hand. All four signed volumes are affine in the sample's
// offset sigma = s - c, so a fragment computes their coefficients once (dcsCoverageSetup) and
// each sample costs four dot products (dcsCovered):
//   det(a - p, c - p, s - p) = A . sigma,       A = cross(a - p, c - p)
//   det(b - p, c - p, s - p) = B . sigma,       B = cross(b - p, c - p)
//   orient(a, b, p, c)       = -k,              k = K . (c - a), K = cross(p - a, b - a)
//   orient(a, b, c, s)       = K2 . sigma,      K2 = cross(b - a, c - a)
//   orient(a, b, s, p)       = K . sigma + k
// Written with sigma (small) rather than s (possibly far from the origin), nothing cancels when
// the light is far. A vertex's side of the triangle's plane depends on that vertex alone, so
// edges sharing a vertex decide identically about it: a path passing near the projection of a
// shared vertex is counted by exactly one of the edges that fold there, never by both or
// neither.
struct DcsCoverage {
  vec3 A, B, K, K2;
  float k;
};

// ne and dc are n_e and n_e . (c - p) from penumbraEdgePlaneDistance (volume_count.h): K = -n_e and k = -dc (equal
// mathematically, det(a - p, b - a, c - a) = det(a - p, b - a, c - p)); taking them from there
// makes the flip below the same decision as the update's sign and the shadow-volume count.
DcsCoverage dcsCoverageSetup(vec3 p, vec3 a, vec3 b, vec3 c, vec3 ne, float dc) {
  DcsCoverage v;
  v.A = cross(a - p, c - p);
  v.B = cross(b - p, c - p);
  // orient(a, b, p, c) < 0 (dc < 0): flip so that the three side tests read ">= 0".
  float flip = dc >= 0.0 ? -1.0 : 1.0;
  v.K = flip * ne;
  v.K2 = -flip * cross(b - a, c - a);
  v.k = flip * dc;
  return v;
}

bool dcsCovered(DcsCoverage v, vec3 sigma) {
  float da = dot(v.A, sigma);
  float db = dot(v.B, sigma);
  if ((da > 0.0) == (db > 0.0)) return false;
  return dot(v.K2, sigma) >= 0.0 && dot(v.K, sigma) + v.k >= 0.0;
}

