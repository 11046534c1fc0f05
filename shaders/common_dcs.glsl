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
struct DcsEdge {
  vec4 v0;     // xyz
  vec4 v1;     // xyz
  ivec4 meta;  // x first incidence, y incidence count, z 1 for the closed-mesh rule
};
struct DcsIncidence {
  vec4 third;   // xyz: the triangle's vertex opposite the edge
  vec4 normal;  // xyz: the triangle's (unnormalised) plane normal in its own winding
};
layout(std430, binding = PENUMBRA_SSBO_DCS_EDGES) readonly buffer DcsEdges { DcsEdge dcsEdges[]; };
layout(std430, binding = PENUMBRA_SSBO_DCS_INCIDENCES) readonly buffer DcsIncidences {
  DcsIncidence dcsIncidences[];
};

int signOf(float x) { return x > 0.0 ? 1 : (x < 0.0 ? -1 : 0); }

// m_e(p) above.
int dcsEdgeWeight(DcsEdge e, vec3 p, vec3 ne) {
  int m = 0;
  for (int k = 0; k < e.meta.y; ++k) {
    DcsIncidence t = dcsIncidences[e.meta.x + k];
    int sigma = signOf(dot(ne, t.third.xyz - p));
    int w = e.meta.z != 0 ? int(dot(t.normal.xyz, p - e.v0.xyz) < 0.0) : 1;
    m += w * sigma;
  }
  return m;
}

// Is sample s separated from c by e as seen from p? Exactly when the segment e = (a, b) passes
// through the triangle (p, c, s) (exact per-sample test; the edge LUT of section 7.3 comes
// later). The test is written so that edges sharing a vertex decide identically about it: a
// vertex's side of the triangle's plane, det(v - p, c - p, s - p), depends on the vertex alone,
// so a path passing near the projection of a shared vertex is counted by exactly one of the
// edges that fold there, never by both or neither.
bool dcsCovered(vec3 p, vec3 a, vec3 b, vec3 c, vec3 s) {
  // cross(c - p, s - c) == cross(c - p, s - p), but does not cancel when the light is far.
  vec3 nt = cross(c - p, s - c);
  float da = dot(a - p, nt);
  float db = dot(b - p, nt);
  if (!((da > 0.0 && db <= 0.0) || (da <= 0.0 && db > 0.0))) return false;
  vec3 q = a + (da / (da - db)) * (b - a);
  return dot(cross(c - p, q - c), nt) >= 0.0 && dot(cross(s - c, q - c), nt) >= 0.0 &&
         dot(cross(p - s, q - s), nt) >= 0.0;
}
