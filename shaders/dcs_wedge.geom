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
// This differs from the paper's outer and inner half-wedges (Fig. 7): the exact per-fragment
// integration must see each (pixel, edge) pair exactly once, and the two halves of a wedge can
// overlap in screen space. A convex polyhedron seen from outside covers every pixel exactly once
// with its front faces, and the fragment's sign is computed per pixel (common_dcs.glsl), so one
// polyhedron per edge replaces the two halves. Only its front faces are emitted, depth-tested
// against the visible surface (a fragment survives only where the surface lies behind the face,
// i.e. may be inside); the fragment shader rejects points beyond the wedge. When the camera may
// be inside the polyhedron or within the near-plane distance of it (its faces would be clipped
// by the near plane), the screen rectangle is drawn instead.
#include "common_dcs.glsl"

layout(points) in;
layout(triangle_strip, max_vertices = 20) out;

uniform mat4 clipFromWorld;
uniform vec3 lightCorners[8];
uniform int lightCornerCount;  // 1 (point), 4 (a planar light's polygon) or 8 (a sphere's cube)
uniform vec3 eyePosition;
uniform float nearRadius;  // the largest distance from the eye to a point of the near plane window
uniform float margin;      // world-space growth of the wedge

flat in int vEdge[];
flat out int gEdge;

void emitVertex(int id, vec4 position) {
  gEdge = id;
  gl_Position = position;
  EmitVertex();
}

const int MAX_CORNERS = 12;
vec3 corner[MAX_CORNERS];
int cornerCount = 0;

void grow(vec4 q, inout vec2 lo, inout vec2 hi, inout bool full) {
  if (q.w <= 1e-7 * (abs(q.x) + abs(q.y))) { full = true; return; }
  vec2 ndc = q.xy / q.w;
  lo = min(lo, ndc);
  hi = max(hi, ndc);
}

// The bounding rectangle of the projected a, b and the vanishing points of the directions
// a - x_j, b - x_j; the whole screen when one of them points behind the camera. Drawn at the
// near plane (depth 1) so that the depth test keeps every pixel.
void emitRectangle(int id, vec3 a, vec3 b) {
  PROFILE_COUNT(profRectangleEdges);
  vec2 lo = vec2(1e30), hi = vec2(-1e30);
  bool full = false;
  grow(clipFromWorld * vec4(a, 1.0), lo, hi, full);
  grow(clipFromWorld * vec4(b, 1.0), lo, hi, full);
  for (int j = 0; j < cornerCount; ++j) {
    grow(clipFromWorld * vec4(a - corner[j], 0.0), lo, hi, full);
    grow(clipFromWorld * vec4(b - corner[j], 0.0), lo, hi, full);
  }
  if (full) { lo = vec2(-1.0); hi = vec2(1.0); }
  lo = max(lo, vec2(-1.0));
  hi = min(hi, vec2(1.0));
  if (lo.x >= hi.x || lo.y >= hi.y) return;
  emitVertex(id, vec4(lo.x, lo.y, 1.0, 1.0));
  emitVertex(id, vec4(hi.x, lo.y, 1.0, 1.0));
  emitVertex(id, vec4(lo.x, hi.y, 1.0, 1.0));
  emitVertex(id, vec4(hi.x, hi.y, 1.0, 1.0));
  EndPrimitive();
}

void emitQuad(int id, vec4 p0, vec4 p1, vec4 p2, vec4 p3) {  // strip order
  emitVertex(id, p0);
  emitVertex(id, p1);
  emitVertex(id, p2);
  emitVertex(id, p3);
  EndPrimitive();
}

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

float outside(vec4 plane) { return dot(plane.xyz, eyePosition) - plane.w; }  // < 0: eye outside

// Case 1: five faces, the four above plus a cap: pushing the front and back planes out moves
// their meeting line back by margin / sin(half the dihedral angle), without bound for a thin
// wedge, so the plane through e perpendicular to the bisector of r_f and r_b (W is on its far
// side) is pushed out too and cuts that off. Returns false when e's line does not miss L_e, the
// solid is degenerate, or the camera is too close.
bool emitWedge(int id, vec3 a, vec3 b) {
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
  float s = cross2(rf2, rb2);  // > 0

  // Side planes: phi through a and the tangent corners, then lowered until every corner fits
  // (beta_j, gamma_j: the corner's perpendicular direction in the (r_f, r_b) basis).
  vec2 phi = vec2(alpha[jf] / length(w[jf]), alpha[jb] / length(w[jb]));
  vec2 psi = vec2(-(alpha[jf] + len) / length(w[jf]), -(alpha[jb] + len) / length(w[jb]));
  float slackA = 0.0, slackB = 0.0;
  for (int j = 0; j < cornerCount; ++j) {
    vec2 bg = max(vec2(cross2(w[j], rb2), cross2(rf2, w[j])) / s, vec2(0.0));
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
  vec4 F = pushedPlane(dot(nF, rb) < 0.0 ? -nF : nF, a);
  vec4 B = pushedPlane(dot(nB, rf) < 0.0 ? -nB : nB, a);
  vec4 C = pushedPlane(normalize(rf + rb), a);
  vec4 A = pushedPlane(dot(nA, d) < 0.0 ? -nA : nA, a);
  vec4 Z = pushedPlane(dot(nZ, d) > 0.0 ? -nZ : nZ, b);
  bool ok = true;
  vec3 fa = meet(F, C, A, ok), ba = meet(B, C, A, ok), fz = meet(F, C, Z, ok), bz = meet(B, C, Z, ok);
  // The cap must run from side a to side b on both faces (not so for an edge shorter than the
  // margin with steep sides: the solid would have other vertices).
  ok = ok && dot(fz - fa, d) > 0.0 && dot(bz - ba, d) > 0.0;
  float hF = outside(F), hB = outside(B), hC = outside(C), hA = outside(A), hZ = outside(Z);
  if (!ok || min(min(min(hF, hB), min(hA, hZ)), hC) >= -nearRadius) return false;
  PROFILE_COUNT(profWedgeEdges);
  vec4 FA = clipFromWorld * vec4(fa, 1.0), BA = clipFromWorld * vec4(ba, 1.0);
  vec4 FZ = clipFromWorld * vec4(fz, 1.0), BZ = clipFromWorld * vec4(bz, 1.0);
  vec4 DF = clipFromWorld * vec4(dF, 0.0), DB = clipFromWorld * vec4(dB, 0.0);
  vec4 EF = clipFromWorld * vec4(eF, 0.0), EB = clipFromWorld * vec4(eB, 0.0);
  // Front faces: those whose plane has the eye outside.
  if (hF < 0.0) emitQuad(id, FA, FZ, DF, EF);
  if (hB < 0.0) emitQuad(id, BA, BZ, DB, EB);
  if (hC < 0.0) emitQuad(id, FA, FZ, BA, BZ);
  if (hA < 0.0) emitQuad(id, FA, BA, DF, DB);
  if (hZ < 0.0) emitQuad(id, FZ, BZ, EF, EB);
  return true;
}

// Case 2: apex q, the other endpoint o. W is inside q + cone(q - ball(c, r)) when o - q points
// into that cone; the square pyramid around the cone has faces n_k . (x - q) >= 0 with
// n_k = sin(theta) axis + cos(theta) u_k, sin(theta) = r / |q - c|, pushed out by margin and
// capped by the plane through q perpendicular to the axis, pushed out too (as in case 1).
bool emitPyramid(int id, vec3 q, vec3 o, vec3 c, float r) {
  vec3 axis = q - c;
  float dist = length(axis);
  if (dist <= 1.001 * r) return false;
  axis /= dist;
  float sinT = r / dist, cosT = sqrt(1.0 - sinT * sinT);
  if (dot(normalize(o - q), axis) < cosT) return false;
  vec3 u = normalize(abs(axis.x) < 0.9 ? cross(axis, vec3(1, 0, 0)) : cross(axis, vec3(0, 1, 0)));
  vec3 v = cross(axis, u);
  float tanT = sinT / cosT;
  // Face k lies between dirs[k] and dirs[k + 1] (its normal is perpendicular to both).
  vec3 dirs[4] = vec3[4](axis + tanT * (u + v), axis + tanT * (v - u), axis - tanT * (u + v), axis + tanT * (u - v));
  vec4 faces[4] = vec4[4](pushedPlane(sinT * axis - cosT * v, q), pushedPlane(sinT * axis + cosT * u, q),
                          pushedPlane(sinT * axis + cosT * v, q), pushedPlane(sinT * axis - cosT * u, q));
  vec4 cap = pushedPlane(axis, q);
  bool ok = true;
  vec4 corners[4], D[4];
  float h[4];
  for (int k = 0; k < 4; ++k) {
    corners[k] = clipFromWorld * vec4(meet(faces[(k + 3) % 4], faces[k], cap, ok), 1.0);
    D[k] = clipFromWorld * vec4(dirs[k], 0.0);
    h[k] = outside(faces[k]);
  }
  float hCap = outside(cap);
  if (!ok || min(min(min(h[0], h[1]), min(h[2], h[3])), hCap) >= -nearRadius) return false;
  PROFILE_COUNT(profWedgeEdges);
  for (int k = 0; k < 4; ++k)
    if (h[k] < 0.0) emitQuad(id, corners[k], corners[(k + 1) % 4], D[k], D[(k + 1) % 4]);
  if (hCap < 0.0) emitQuad(id, corners[0], corners[1], corners[3], corners[2]);
  return true;
}

void main() {
  int id = vEdge[0];
  DcsEdge e = dcsEdges[id];
  vec3 a = e.v0.xyz, b = e.v1.xyz;
  if (a == b) return;  // a point separates no path from another
  lightPart(e);
  if (cornerCount == 0) return;  // e is a silhouette from no point of the light
  if (emitWedge(id, a, b)) return;
  vec3 c = vec3(0.0);
  for (int j = 0; j < cornerCount; ++j) c += corner[j];
  c /= float(cornerCount);
  float r = 0.0;
  for (int j = 0; j < cornerCount; ++j) r = max(r, length(corner[j] - c));
  r *= 1.0001;
  if (emitPyramid(id, b, a, c, r) || emitPyramid(id, a, b, c, r)) return;
  emitRectangle(id, a, b);
}
