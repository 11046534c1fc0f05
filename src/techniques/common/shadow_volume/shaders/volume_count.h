// The shadow-volume count (hard-sv, dcs's integration constant) and dcs's wedges: which faces of
// the volumes the view ray meets, decided exactly, the same in C++ (volume_cover.cpp, the tests)
// and the shaders. Valid in both (shared/shared.h); C++ includes it through
// techniques/common/shadow_volume/volume_count.hpp.
#ifndef PENUMBRA_VOLUME_COUNT_H
#define PENUMBRA_VOLUME_COUNT_H

#include "shared/shared.h"


PENUMBRA_FN float penumbraDet3(vec3 a, vec3 b, vec3 c) {
  PENUMBRA_PRECISE float r = dot(a, cross(b, c));
  return r;
}

// The plane through an edge (v0, v1) and a point x: the shadow-volume count (which side of a
// volume side the visible point lies on) and the dcs wedges (on which side of plane(p, e) the
// light centre lies, which chooses the sign of the edge's update) evaluate the sign of the same
// determinant det(v0 - x, v1 - v0, c - x) through this one function, precise, so that for a point
// within rounding of a side plane the integration constant D(c) and the wedge updates agree:
// D(s) = D(c) + sum of updates is then right on the centre's hard-shadow boundary too. n_e is
// written with the short edge vector v1 - v0 (accurate for edges seen end-on, common_dcs.glsl).
// Mathematically det(v0 - x, v1 - v0, c - x) = det(v0 - c, v1 - c, c - x).
PENUMBRA_FN float penumbraEdgePlaneDistance(vec3 v0, vec3 v1, vec3 c, vec3 x, PENUMBRA_OUT(vec3) ne) {
  PENUMBRA_PRECISE vec3 n = cross(v0 - x, v1 - v0);
  PENUMBRA_PRECISE float d = dot(n, c - x);
  ne = n;
  return d;
}

// +1 when c lies on the side of plane(x, e) that n_e points to (or on it), else -1.
PENUMBRA_FN int penumbraSideOfEdgePlane(vec3 v0, vec3 v1, vec3 c, vec3 x) {
  vec3 ne = vec3(0.0f);
  return penumbraEdgePlaneDistance(v0, v1, c, x, ne) >= 0.0f ? 1 : -1;
}

// Which faces of the shadow volumes the view ray meets (src/techniques/common/shadow_volume/shaders/hardsv_volume.frag). The count at
// a visible point o is the sum, over the volume faces the ray from the eye through o meets beyond
// o, of -w where the face is seen from its front and +w from its back (z-fail, Everitt and
// Kilgard 2002). Whether the ray meets a face is decided exactly here, not by the rasteriser:
// rasterisation snaps vertices to its sub-pixel grid, so near the line where two faces meet the
// face it gives a pixel to can be the wrong one. That is harmless while the two crossings lie on
// one side of o, but a view ray through the line from the light through a vertex (hard case 34)
// meets both faces there, near o, one before and one after it: the engine scene at 128 px had a
// pixel whose count was 11 where the volumes hold 13 (an edge-on side face rasterised across the
// line that the exact geometry kept it from).
//
// The line through o with direction d meets a convex polygon exactly when its Plücker products
// with the polygon's edges, taken around the polygon, all have one sign; that sign is +1 where
// the polygon is seen from its front (its normal by the right-hand rule faces the eye). The
// product with an edge P -> Q (homogeneous points, w = 0 at infinity) is
// det[P; Q; (o, 1); (d, 0)]. Each edge's product is computed by one function of the edge alone,
// with the edge put in a canonical order and the result negated for the other order, so the
// faces that share an edge (a side and its neighbour along a vertex line, a side and the cap
// along an occluder edge, a side and the far cap at infinity) take exactly opposite values and
// the ray meets exactly one of two faces folding apart there, or both or neither of two folded
// together: the volumes stay watertight whatever rounding does. A product of exactly 0 counts as
// +1 in the canonical order.
// The rasteriser only hands the fragment shader candidate pixels: each face is drawn grown on
// screen by a margin above the rasteriser's snapping (techniques/shadow_volume/volume_cover.h).
PENUMBRA_FN bool penumbraLexLess(vec3 a, vec3 b) {
  return a.x != b.x ? a.x < b.x : (a.y != b.y ? a.y < b.y : a.z < b.z);
}

// Edge a -> b between finite points: -det(a - o, b - o, d), written with the edge vector
// (-det(a - o, b - a, d)) so that its rounding is that of the point's distance, not its square.
// With the light centre c in place of o, the edge a_inf -> b_inf at infinity between the
// directions a - c and b - c: -det(a - c, b - c, d) = -det(a - c, b - a, d).
PENUMBRA_FN int penumbraViewEdgeSide(vec3 a, vec3 b, vec3 o, vec3 d) {
  bool swapped = penumbraLexLess(b, a);
  vec3 u = swapped ? b : a;
  vec3 v = swapped ? a : b;
  int s = -penumbraDet3(u - o, v - u, d) >= 0.0f ? 1 : -1;
  return swapped ? -s : s;
}

// The edge from a vertex v to infinity away from the light centre c (a vertex line): the product
// is (v - c) . n with n = cross(d, o - c), one vector per pixel, so it depends on v alone; the
// edge from infinity back to v has the opposite sign.
PENUMBRA_FN int penumbraViewVertexLineSide(vec3 v, vec3 c, vec3 n) {
  PENUMBRA_PRECISE float s = dot(v - c, n);
  return s >= 0.0f ? 1 : -1;
}

// What a side of edge (v0, v1) (in the edge's own order; weight w = m_e times the mesh's units,
// its sign turning the quad to face out of the volume) adds to the count at o: the quad
// b -> a -> a_inf -> b_inf with (a, b) = (v0, v1), swapped for w < 0. It lies beyond o where o
// and the ray's direction are on opposite sides of the side's plane (the plane through c): o's
// side is penumbraSideOfEdgePlane, the very decision dcs's wedges take for the sign of their
// update, and the direction's side is the product with the quad's edge at infinity.
PENUMBRA_FN float penumbraSideCount(vec3 v0, vec3 v1, float w, vec3 c, vec3 o, vec3 d, vec3 n) {
  vec3 a = w < 0.0f ? v1 : v0;
  vec3 b = w < 0.0f ? v0 : v1;
  int s = penumbraViewEdgeSide(b, a, o, d);
  if (penumbraViewVertexLineSide(a, c, n) != s || penumbraViewEdgeSide(a, b, c, d) != s ||
      -penumbraViewVertexLineSide(b, c, n) != s)
    return 0.0f;
  if (penumbraSideOfEdgePlane(v0, v1, c, o) != -penumbraViewEdgeSide(v0, v1, c, d)) return 0.0f;
  return s > 0 ? -abs(w) : abs(w);
}

// A near cap (the triangle x -> y -> z, turned to face the light) of weight w.
PENUMBRA_FN float penumbraNearCapCount(vec3 x, vec3 y, vec3 z, float w, vec3 o, vec3 d) {
  int s = penumbraViewEdgeSide(x, y, o, d);
  if (penumbraViewEdgeSide(y, z, o, d) != s || penumbraViewEdgeSide(z, x, o, d) != s) return 0.0f;
  // Beyond o: sign(n . (x - o)) = sign(n . d), and sign(n . d) = -s.
  PENUMBRA_PRECISE vec3 nt = cross(y - x, z - x);
  PENUMBRA_PRECISE float f = dot(nt, o - x);
  if ((f >= 0.0f ? 1 : -1) != s) return 0.0f;
  return s > 0 ? -w : w;
}

#define PENUMBRA_VOLUME_SIDE 0      // face kinds of the count's storage block
#define PENUMBRA_VOLUME_NEAR_CAP 1
#define PENUMBRA_VOLUME_FAR_CAP 2

// The far cap of the triangle x -> y -> z (x, y, z projected to infinity from c, the triangle
// reversed: x_inf -> z_inf -> y_inf), behind every point. The ray's direction d (not -d) lies
// in the cone of the triangle's directions where the common sign is that of det(x - c, y - c,
// z - c).
PENUMBRA_FN float penumbraFarCapCount(vec3 x, vec3 y, vec3 z, float w, vec3 c, vec3 d) {
  int s = penumbraViewEdgeSide(x, z, c, d);
  if (penumbraViewEdgeSide(z, y, c, d) != s || penumbraViewEdgeSide(y, x, c, d) != s) return 0.0f;
  float orientation = penumbraDet3(x - c, y - c, z - c);
  if (orientation == 0.0f || (orientation > 0.0f ? 1 : -1) != s) return 0.0f;
  return s > 0 ? -w : w;
}

#endif
