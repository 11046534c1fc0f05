// The wedge of an edge e = (a, b): the points p whose counters e can change. A change at p
// happens where a path on the light crosses e's projection from p, at a light point y with
// e between p and y: p is in W = e + cone(e - L_e) (p = x + t (x - y), x on e, y in L_e,
// t >= 0; DCS section 4.2, Algorithm 1 line 2; the penumbra wedge of [AAM03]). L_e is the part
// of the light from which e can count at all:
//   edges with two incident triangles: m_e(p) != 0 only where e is a silhouette seen from p
//     (common_dcs.glsl: for the closed-mesh rule m = [p behind t1] - [p behind t2]; for the
//     per-triangle rule m = sigma_1 + sigma_2, non-zero when both triangles lie on one side of
//     plane(p, e)), i.e. p, and so y on the other side of e, is in front of exactly one of them
//     (of both or neither, for two triangles running the edge the same way); L_e = L clipped to
//     that region (two convex pieces; we take both pieces' corners). On a finely tessellated
//     curved surface the two planes are close and L_e is a thin strip of the light, so the wedge
//     is thin: this is the main saving.
//   other edges: L_e = a convex polytope around the light (the rect, a disk's square, a
//     sphere's cube).
// W is bounded by a convex polyhedron, in order of preference:
//   1. e's line misses L_e: four faces, the front and back planes through e tangent to L_e and a
//      side plane through each endpoint with every corner of L_e on the light side. In the frame
//      (d = e's direction; r_f, r_b = the tangent directions away from the light, perpendicular
//      to d) with a - x_j = alpha_j d + beta_j r_f + gamma_j r_b for the corners x_j:
//        { a + alpha d + beta r_f + gamma r_b : beta, gamma >= 0,
//          alpha >= phi_f beta + phi_b gamma, L - alpha >= psi_f beta + psi_b gamma }
//      with phi . (beta_j, gamma_j) <= alpha_j for every corner (and the same for psi at b).
//   2. e's line passes through L_e's bounding ball beyond an endpoint q (an edge pointing at the
//      light): W is inside q + cone(q - ball), bounded by a square pyramid with apex q.
//   3. otherwise (an edge reaching into the light), the screen rectangle bounding W's projection.
// Every plane is pushed out by `margin` (>= the fragment's surface offset), so that a pixel whose
// offset point lies in W has its visible surface point inside the polyhedron, and a cap plane
// keeps the pushed solid from growing without bound behind a thin wedge's edge.
//
// The solid is shared by the raster path (dcs_wedge.geom draws its front faces) and the compute
// path (dcs_wedge.comp tests points against its planes).
#ifndef DCS_SOLID_GLSL
#define DCS_SOLID_GLSL
#include "common_dcs.glsl"

uniform mat4 clipFromWorld;
uniform float margin;      // world-space growth of the wedge

const int MAX_CORNERS = 12;
vec3 corner[MAX_CORNERS];
int cornerCount = 0;

// L_e's corners: the light polygon clipped to {f1 >= 0, f2 <= 0} plus the one clipped to
// {f1 <= 0, f2 >= 0}, f_t(y) = n_t . (y - v0) (Sutherland-Hodgman, with a tolerance that keeps
// the clip conservative).
void clipPiece(vec3 v0, vec3 nFront, vec3 nBack, float size) {
  vec3 poly[8], next[8];
  int count = 4;
  for (int j = 0; j < 4; ++j) poly[j] = lightCorners[j];
  for (int plane = 0; plane < 2; ++plane) {
    vec3 n = plane == 0 ? nFront : -nBack;  // keep n . (y - v0) >= -tol
    float tol = 1e-4 * size * length(n);
    int kept = 0;
    for (int j = 0; j < count; ++j) {
      vec3 p = poly[j], q = poly[(j + 1) % count];
      float fp = dot(n, p - v0) + tol, fq = dot(n, q - v0) + tol;
      if (fp >= 0.0) next[kept++] = p;
      if ((fp >= 0.0) != (fq >= 0.0)) next[kept++] = p + (fp / (fp - fq)) * (q - p);
    }
    count = kept;
    for (int j = 0; j < count; ++j) poly[j] = next[j];
  }
  for (int j = 0; j < count && cornerCount < MAX_CORNERS; ++j) corner[cornerCount++] = poly[j];
}

void lightPart(DcsEdge e) {
  cornerCount = 0;
  if (lightCornerCount == 4 && e.meta.y == 2) {
    DcsIncidence t1 = dcsIncidences[e.meta.x], t2 = dcsIncidences[e.meta.x + 1];
    // Triangles running the edge the same way (an inconsistently wound open mesh) count where
    // the point faces both the same way: flip the second plane.
    vec3 n1 = t1.normal.xyz, n2 = t1.third.w == t2.third.w ? -t2.normal.xyz : t2.normal.xyz;
    float size = 0.0;
    for (int j = 1; j < 4; ++j) size = max(size, length(lightCorners[j] - lightCorners[0]));
    vec3 v0 = e.v0.xyz;
    clipPiece(v0, n1, n2, size);  // in front of t1, behind t2
    clipPiece(v0, n2, n1, size);  // in front of t2, behind t1
    return;
  }
  for (int j = 0; j < lightCornerCount; ++j) corner[cornerCount++] = lightCorners[j];
}

float cross2(vec2 u, vec2 v) { return u.x * v.y - u.y * v.x; }

// A plane n . x >= k (n a unit inward normal) through q, pushed out by margin.
vec4 pushedPlane(vec3 n, vec3 q) { return vec4(n, dot(n, q) - margin); }

// The point on three planes; ok is false when they are (nearly) parallel.
vec3 meet(vec4 p0, vec4 p1, vec4 p2, inout bool ok) {
  vec3 c12 = cross(p1.xyz, p2.xyz), c20 = cross(p2.xyz, p0.xyz), c01 = cross(p0.xyz, p1.xyz);
  float det = dot(p0.xyz, c12);
  ok = ok && abs(det) > 1e-6;
  return (p0.w * c12 + p1.w * c20 + p2.w * c01) / det;
}

const int DCS_SOLID_NONE = 0;     // e separates no two points of the light: no update anywhere
const int DCS_SOLID_WEDGE = 1;    // case 1, planes F, B, C, A, Z
const int DCS_SOLID_PYRAMID = 2;  // case 2, four faces and the cap
const int DCS_SOLID_RECT = 3;     // case 3, no planes: the screen rectangle (rect: NDC lo.xy, hi.xy)
struct DcsSolid {
  int kind;
  vec4 plane[5];   // inward unit normals and offsets: inside is n . x >= w for all five
  vec3 vertex[4];  // WEDGE: fa, ba, fz, bz (side a and side b on F and on B); PYRAMID: the cap's corners
  vec3 dir[4];     // WEDGE: dF, dB, eF, eB, the edges to infinity; PYRAMID: those of the faces
  vec4 rect;       // RECT: NDC bounds (lo.x, lo.y, hi.x, hi.y)
};

// The compute path's copy of a solid, in the storage block PENUMBRA_SSBO_DCS_SOLIDS
// (dcs_solids.comp writes it, dcs_wedge.comp reads it; declared there, the raster path's
// stages declare no writable block).
const int DCS_SIDE_PLANES = 8;
struct DcsSolidPlanes {
  vec4 plane[5];  // DcsSolid::plane (RECT: plane[0] its NDC rectangle)
  ivec4 meta;     // x the kind (DCS_SOLID_*), y the edge id, z the side planes used
  vec4 side[DCS_SIDE_PLANES];  // WEDGE: more planes holding W at its ends (dcsSidePlanes)
};

DcsSolid dcsNoSolid() {
  DcsSolid s;
  s.kind = DCS_SOLID_NONE;
  for (int k = 0; k < 5; ++k) s.plane[k] = vec4(0.0);
  for (int k = 0; k < 4; ++k) s.vertex[k] = s.dir[k] = vec3(0.0);
  s.rect = vec4(0.0);
  return s;
}

void grow(vec4 q, inout vec2 lo, inout vec2 hi, inout bool full) {
  if (q.w <= 1e-7 * (abs(q.x) + abs(q.y))) { full = true; return; }
  vec2 ndc = q.xy / q.w;
  lo = min(lo, ndc);
  hi = max(hi, ndc);
}

// Case 3: the bounding rectangle of the projected a, b and the vanishing points of the
// directions a - x_j, b - x_j; the whole screen when one of them points behind the camera.
vec4 screenRectangle(vec3 a, vec3 b) {
  vec2 lo = vec2(1e30), hi = vec2(-1e30);
  bool full = false;
  grow(clipFromWorld * vec4(a, 1.0), lo, hi, full);
  grow(clipFromWorld * vec4(b, 1.0), lo, hi, full);
  for (int j = 0; j < cornerCount; ++j) {
    grow(clipFromWorld * vec4(a - corner[j], 0.0), lo, hi, full);
    grow(clipFromWorld * vec4(b - corner[j], 0.0), lo, hi, full);
  }
  if (full) { lo = vec2(-1.0); hi = vec2(1.0); }
  return vec4(max(lo, vec2(-1.0)), min(hi, vec2(1.0)));
}

// Case 1: five faces, the four above plus a cap: pushing the front and back planes out moves
// their meeting line back by margin / sin(half the dihedral angle), without bound for a thin
// wedge, so the plane through e perpendicular to the bisector of r_f and r_b (W is on its far
// side) is pushed out too and cuts that off. False when e's line does not miss L_e or the solid
// is degenerate.
bool wedgeSolid(vec3 a, vec3 b, inout DcsSolid s) {
  float len = length(b - a);
  vec3 d = (b - a) / len;
  // Looking along d: the directions w_j from the corners to e's line and their angular range.
  vec3 u = vec3(0.0), v = vec3(0.0);
  vec2 w[MAX_CORNERS];
  float alpha[MAX_CORNERS];
  int jf = 0, jb = 0;
  float angF = 0.0, angB = 0.0;
  for (int j = 0; j < cornerCount; ++j) {
    vec3 toEdge = a - corner[j];
    alpha[j] = dot(toEdge, d);
    vec3 perp = toEdge - alpha[j] * d;
    float pl = length(perp);
    if (pl <= 1e-5 * length(toEdge)) return false;  // e's line (nearly) through a corner
    if (j == 0) {
      u = perp / pl;
      v = cross(d, u);
    }
    w[j] = vec2(dot(perp, u), dot(perp, v));
    float ang = atan(w[j].y, w[j].x);
    if (ang < angF) { angF = ang; jf = j; }
    if (ang > angB) { angB = ang; jb = j; }
  }
  // L_e's projection must lie strictly within a half-plane.
  if (angB - angF > 3.1 || angB - angF < 1e-6) return false;
  vec2 rf2 = normalize(w[jf]), rb2 = normalize(w[jb]);
  vec3 rf = rf2.x * u + rf2.y * v, rb = rb2.x * u + rb2.y * v;
  float sn = cross2(rf2, rb2);  // > 0

  // Side planes: phi through a and the tangent corners, then lowered until every corner fits
  // (beta_j, gamma_j: the corner's perpendicular direction in the (r_f, r_b) basis).
  vec2 phi = vec2(alpha[jf] / length(w[jf]), alpha[jb] / length(w[jb]));
  vec2 psi = vec2(-(alpha[jf] + len) / length(w[jf]), -(alpha[jb] + len) / length(w[jb]));
  float slackA = 0.0, slackB = 0.0;
  for (int j = 0; j < cornerCount; ++j) {
    vec2 bg = max(vec2(cross2(w[j], rb2), cross2(rf2, w[j])) / sn, vec2(0.0));
    float sum = max(bg.x + bg.y, 1e-30);
    slackA = max(slackA, (dot(phi, bg) - alpha[j]) / sum);
    slackB = max(slackB, (dot(psi, bg) + alpha[j] + len) / sum);
  }
  phi -= vec2(slackA);
  psi -= vec2(slackB);
  vec3 dF = phi.x * d + rf, dB = phi.y * d + rb;   // the edges of side a, to infinity
  vec3 eF = -psi.x * d + rf, eB = -psi.y * d + rb;  // the edges of side b, to infinity

  // The five pushed planes, inward unit normals.
  vec3 nF = normalize(cross(d, rf));
  vec3 nB = normalize(cross(d, rb));
  vec3 nA = normalize(cross(dF, dB));
  vec3 nZ = normalize(cross(eF, eB));
  s.plane[0] = pushedPlane(dot(nF, rb) < 0.0 ? -nF : nF, a);  // F
  s.plane[1] = pushedPlane(dot(nB, rf) < 0.0 ? -nB : nB, a);  // B
  s.plane[2] = pushedPlane(normalize(rf + rb), a);            // C
  s.plane[3] = pushedPlane(dot(nA, d) < 0.0 ? -nA : nA, a);   // A
  s.plane[4] = pushedPlane(dot(nZ, d) > 0.0 ? -nZ : nZ, b);   // Z
  bool ok = true;
  vec4 F = s.plane[0], B = s.plane[1], C = s.plane[2], A = s.plane[3], Z = s.plane[4];
  s.vertex[0] = meet(F, C, A, ok);
  s.vertex[1] = meet(B, C, A, ok);
  s.vertex[2] = meet(F, C, Z, ok);
  s.vertex[3] = meet(B, C, Z, ok);
  // The cap must run from side a to side b on both faces (not so for an edge shorter than the
  // margin with steep sides: the solid would have other vertices).
  ok = ok && dot(s.vertex[2] - s.vertex[0], d) > 0.0 && dot(s.vertex[3] - s.vertex[1], d) > 0.0;
  s.dir[0] = dF;
  s.dir[1] = dB;
  s.dir[2] = eF;
  s.dir[3] = eB;
  s.kind = DCS_SOLID_WEDGE;
  return ok;
}

// The compute path's extra planes of a WEDGE solid (after dcsSolidBegin: corner[] holds L_e),
// where it can test more planes per point than the raster path draws faces: W's end at a is
// bounded by the cone a + cone(a - L_e) (p - a = s (1 + t) d + t (a - y) with x = a + s d on e,
// y in L_e, s, t >= 0), which the single side plane A bounds loosely when L_e spans a wide angle
// along e (a large light, a short edge). Every plane through a and two corners x_i, x_j that has
// every a - x_k and d on its inner side holds W, and so does their intersection: these are the
// cone's faces that face along d (at b the same with -d). Pushed out by margin like the others;
// the first DCS_SIDE_PLANES found. Returns their number.
int dcsSidePlanes(vec3 a, vec3 b, out vec4 side[DCS_SIDE_PLANES]) {
  int count = 0;
  for (int end = 0; end < 2; ++end) {
    vec3 q = end == 0 ? a : b, along = end == 0 ? b - a : a - b;
    for (int i = 0; i < cornerCount; ++i)
      for (int j = i + 1; j < cornerCount; ++j) {
        vec3 n = cross(corner[i] - q, corner[j] - q);
        float nl = length(n);
        if (nl <= 1e-6 * length(corner[i] - q) * length(corner[j] - q)) continue;
        n /= nl;
        // Every corner direction q - x_k on one side (to rounding), then that side inward.
        float lo = 0.0, hi = 0.0;
        for (int k = 0; k < cornerCount; ++k) {
          float sk = dot(n, q - corner[k]), tol = 1e-6 * length(q - corner[k]);
          lo = min(lo, sk + tol);
          hi = max(hi, sk - tol);
        }
        if (lo < 0.0 && hi > 0.0) continue;  // corners on both sides: not a face of the cone
        if (lo < 0.0) n = -n;
        if (dot(n, along) < 0.0 || count == DCS_SIDE_PLANES) continue;  // cuts e itself, or no room
        side[count++] = pushedPlane(n, q);
      }
  }
  for (int k = count; k < DCS_SIDE_PLANES; ++k) side[k] = vec4(0.0);
  return count;
}

// Case 2: apex q, the other endpoint o. W is inside q + cone(q - ball(c, r)) when o - q points
// into that cone; the square pyramid around the cone has faces n_k . (x - q) >= 0 with
// n_k = sin(theta) axis + cos(theta) u_k, sin(theta) = r / |q - c|, pushed out by margin and
// capped by the plane through q perpendicular to the axis, pushed out too (as in case 1).
bool pyramidSolid(vec3 q, vec3 o, vec3 c, float r, inout DcsSolid s) {
  vec3 axis = q - c;
  float dist = length(axis);
  if (dist <= 1.001 * r) return false;
  axis /= dist;
  float sinT = r / dist, cosT = sqrt(1.0 - sinT * sinT);
  if (dot(normalize(o - q), axis) < cosT) return false;
  vec3 u = normalize(abs(axis.x) < 0.9 ? cross(axis, vec3(1, 0, 0)) : cross(axis, vec3(0, 1, 0)));
  vec3 v = cross(axis, u);
  float tanT = sinT / cosT;
  // Face k lies between dir[k] and dir[k + 1] (its normal is perpendicular to both).
  s.dir[0] = axis + tanT * (u + v);
  s.dir[1] = axis + tanT * (v - u);
  s.dir[2] = axis - tanT * (u + v);
  s.dir[3] = axis + tanT * (u - v);
  s.plane[0] = pushedPlane(sinT * axis - cosT * v, q);
  s.plane[1] = pushedPlane(sinT * axis + cosT * u, q);
  s.plane[2] = pushedPlane(sinT * axis + cosT * v, q);
  s.plane[3] = pushedPlane(sinT * axis - cosT * u, q);
  s.plane[4] = pushedPlane(axis, q);  // the cap
  bool ok = true;
  for (int k = 0; k < 4; ++k) s.vertex[k] = meet(s.plane[(k + 3) % 4], s.plane[k], s.plane[4], ok);
  s.kind = DCS_SOLID_PYRAMID;
  return ok;
}

// Edge e's part of the light (lightPart); false when e needs no solid (no update anywhere).
bool dcsSolidBegin(DcsEdge e) {
  if (e.v0.xyz == e.v1.xyz) return false;  // a point separates no path from another
  lightPart(e);
  return cornerCount > 0;  // else e is a silhouette from no point of the light
}

// Case k of edge e (after dcsSolidBegin): 1 the wedge, 2 the pyramid with apex v1, 3 with
// apex v0; false when it does not apply.
bool dcsSolidCase(int k, DcsEdge e, inout DcsSolid s) {
  vec3 a = e.v0.xyz, b = e.v1.xyz;
  if (k == 1) return wedgeSolid(a, b, s);
  vec3 c = vec3(0.0);
  for (int j = 0; j < cornerCount; ++j) c += corner[j];
  c /= float(cornerCount);
  float r = 0.0;
  for (int j = 0; j < cornerCount; ++j) r = max(r, length(corner[j] - c));
  r *= 1.0001;
  return k == 2 ? pyramidSolid(b, a, c, r, s) : pyramidSolid(a, b, c, r, s);
}

// The solid of edge e: the first of cases 1-3 that applies.
DcsSolid dcsSolid(DcsEdge e) {
  DcsSolid s = dcsNoSolid();
  if (!dcsSolidBegin(e)) return s;
  if (dcsSolidCase(1, e, s) || dcsSolidCase(2, e, s) || dcsSolidCase(3, e, s)) return s;
  s.kind = DCS_SOLID_RECT;
  s.rect = screenRectangle(e.v0.xyz, e.v1.xyz);
  return s;
}

#endif
