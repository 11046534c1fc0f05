// The raster path's wedges: one point per selected edge in, the front faces of its solid
// (dcs_solid.glsl) out.
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
//
// A wedge solid is drawn cut by the compute path's end planes (dcsSidePlanes: the faces of the
// cones q + cone(q - L_e) at the endpoints q that face along the edge) and by the view:
// the five-plane solid is loose where a large light meets a short edge, and every surface behind
// its front faces costs a fragment (engine, 256^2, 16 samples: 28.5 M -> 8.8 M). The polyhedron
// is built here (wedgePolyhedron, cutPolyhedron) in homogeneous world coordinates, its points at
// infinity having w = 0, by clipping each face polygon and closing every cut with the polygon of
// its crossing points; a crossing point is computed from its edge's two endpoints in one order
// (inside first), so the faces that share an edge share its vertices to the bit.
//
// Faces seen nearly edge-on are slivers thinner than the rasteriser's sub-pixel grid; snapped,
// one can fold over its neighbour, and two front faces then cover a pixel (measured: one pair of
// the engine at 64 px, where the compute path sees each pair once). The polygons are kept
// consistently oriented (each edge runs one way in one face and the other way in the other), and
// every front face of a wedge is drawn with the orientation gFacing says it has unfolded: a
// fragment whose gl_FrontFacing disagrees (a folded sliver) counts with the opposite sign
// (dcs_wedge.frag). The signed coverage of the front faces is the winding number of their
// outline, 1 inside it however their inner edges fold. Where rounding has left the polyhedron
// itself not convex (orientedAsFacing), its outline cannot be trusted: the next solid is drawn
// (in the end the screen rectangle, which covers each pixel once).
#include "dcs_solid.glsl"

layout(points) in;
layout(triangle_strip, max_vertices = 96) out;

uniform vec3 eyePosition;
uniform float nearRadius;  // the largest distance from the eye to a point of the near plane window

flat in int vEdge[];
flat out int gEdge;
flat out int gFacing;  // +1 / -1: the gl_FrontFacing a fragment of an unfolded face has; 0: any
int facing = 0;

void emitVertex(int id, vec4 position) {
  gEdge = id;
  gFacing = facing;
  gl_Position = position;
  EmitVertex();
}

// Drawn at the near plane (depth 1) so that the depth test keeps every pixel.
void emitRectangle(int id, vec4 r) {
  PROFILE_COUNT(profRectangleEdges);
  facing = 0;
  if (r.x >= r.z || r.y >= r.w) return;
  emitVertex(id, vec4(r.x, r.y, 1.0, 1.0));
  emitVertex(id, vec4(r.z, r.y, 1.0, 1.0));
  emitVertex(id, vec4(r.x, r.w, 1.0, 1.0));
  emitVertex(id, vec4(r.z, r.w, 1.0, 1.0));
  EndPrimitive();
}

float outside(vec4 plane) { return dot(plane.xyz, eyePosition) - plane.w; }  // < 0: eye outside

// The (cut) wedge: faces 0-4 the wedge's F, B, C, A, Z, 5 its face at infinity (never drawn, but
// cut like the others: a cut polygon may run along it), then one face per cutting plane. Every
// polygon runs the same way around its face's outward normal (which way: wedgePolyhedron).
const int POLY_FACES = 6 + DCS_SIDE_PLANES + 4;
const int POLY_CORNERS = 16;  // a convex polygon gains at most one corner per cut
const int POLY_EMITTED = 96;  // max_vertices
vec4 polyCorner[POLY_FACES][POLY_CORNERS];
int polyCount[POLY_FACES];
vec4 polyPlane[POLY_FACES];  // the face's plane (inward); faces never drawn: vec4(0)

// Inside: n . x - w k >= 0 for the homogeneous point (x, w).
float planeValue(vec4 plane, vec4 x) { return dot(plane.xyz, x.xyz) - plane.w * x.w; }

// The point of segment (i, o) on the plane, i inside (fi >= 0), o outside (fo < 0): a positive
// combination (w stays >= 0), scaled so that its largest component is 1.
vec4 crossing(vec4 i, float fi, vec4 o, float fo) {
  vec4 x = (-fo) * i + fi * o;
  float m = max(max(abs(x.x), abs(x.y)), max(abs(x.z), abs(x.w)));
  return x / m;
}

void setFace(int f, vec4 plane, vec4 c0, vec4 c1, vec4 c2, vec4 c3) {
  polyPlane[f] = plane;
  polyCorner[f][0] = c0;
  polyCorner[f][1] = c1;
  polyCorner[f][2] = c2;
  polyCorner[f][3] = c3;
  polyCount[f] = 4;
}

// Cuts the solid of faces [0, faces) by plane and adds the cut polygon as face `faces`; false
// when the cut polygon does not close or a polygon has no room.
bool cutPolyhedron(vec4 plane, int faces) {
  polyPlane[faces] = plane;
  polyCount[faces] = 0;
  // A plane nearly parallel to a face it cuts would leave an almost flat edge between that face
  // and the cut polygon, a sliver or two: skipped (the solid only gets looser).
  for (int f = 0; f < faces; ++f) {
    if (polyCount[f] == 0 || f == 5 || abs(dot(plane.xyz, polyPlane[f].xyz)) < 0.999) continue;
    bool kept = false, cut = false;
    for (int j = 0; j < polyCount[f]; ++j) {
      float v = planeValue(plane, polyCorner[f][j]);
      kept = kept || v >= 0.0;
      cut = cut || v < 0.0;
    }
    if (kept && cut) return true;
  }
  // Each face that the plane crosses leaves it at x and comes back at y (in its polygon's
  // order): its new edge runs x -> y, so the cut polygon's runs y -> x.
  vec4 from[POLY_FACES], to[POLY_FACES];
  int segments = 0;
  for (int f = 0; f < faces; ++f) {
    int n = polyCount[f];
    if (n == 0) continue;
    vec4 next[POLY_CORNERS];
    int kept = 0, leaves = 0, enters = 0;
    for (int j = 0; j < n; ++j) {
      vec4 p = polyCorner[f][j], q = polyCorner[f][(j + 1) % n];
      float fp = planeValue(plane, p), fq = planeValue(plane, q);
      if (kept == POLY_CORNERS) return false;
      if (fp >= 0.0) next[kept++] = p;
      if ((fp >= 0.0) == (fq >= 0.0)) continue;
      if (kept == POLY_CORNERS || segments == POLY_FACES) return false;
      vec4 x = fp >= 0.0 ? crossing(p, fp, q, fq) : crossing(q, fq, p, fp);
      next[kept++] = x;
      if (fp >= 0.0) {
        to[segments] = x;
        ++leaves;
      } else {
        from[segments] = x;
        ++enters;
      }
    }
    if (leaves != enters || leaves > 1) return false;
    segments += leaves;
    polyCount[f] = kept;
    for (int j = 0; j < kept; ++j) polyCorner[f][j] = next[j];
  }
  if (segments == 0) return true;  // the plane cuts nothing off (or everything: no faces left)
  if (segments < 3) return false;
  // Chain the segments: each one starts where another ends.
  polyCorner[faces][0] = from[0];
  vec4 current = to[0];
  int used = 1;  // bit s: segment s is in the chain
  for (int k = 1; k < segments; ++k) {
    polyCorner[faces][k] = current;
    int next = -1;
    for (int s = 1; s < segments && next < 0; ++s)
      if ((used & (1 << s)) == 0 && from[s] == current) next = s;
    if (next < 0) return false;
    used |= 1 << next;
    current = to[next];
  }
  if (current != from[0]) return false;
  polyCount[faces] = segments;
  return true;
}

// The frustum's side planes a little outside the screen (k: +x, +y, -x, -y), which also cut
// off everything behind the eye: cut by them, the polyhedron gives the rasteriser corners of
// bounded window coordinates only, not those of the wedge's far edges (without it a pixel next to
// the shared edge of two front faces whose far end lay 55 px off the screen was rasterised by
// both: engine, 64 px, llvmpipe). Their cut polygons are not drawn.
vec4 viewPlane(int k) {
  const float guard = 1.25;  // NDC
  mat4 m = transpose(clipFromWorld);  // rows: x, y, z, w of clip space
  vec4 clip = guard * m[3] - (k < 2 ? m[k] : -m[k - 2]);  // clip . X >= 0 on the screen's side
  clip /= length(clip.xyz);
  return vec4(clip.xyz, -clip.w);
}

// Wedge solid s as polygons, each edge running one way in one face and the other way in the
// other; returns the facing of an unfolded front face: +1 when the polygons run
// counter-clockwise around the outward normals (F's order V0, V2, D2 against -plane[0]).
int wedgePolyhedron(DcsSolid s) {
  vec4 V[4], D[4];
  for (int k = 0; k < 4; ++k) {
    V[k] = vec4(s.vertex[k], 1.0);
    D[k] = vec4(s.dir[k], 0.0);
  }
  setFace(0, s.plane[0], V[0], V[2], D[2], D[0]);  // F
  setFace(1, s.plane[1], V[3], V[1], D[1], D[3]);  // B
  setFace(2, s.plane[2], V[2], V[0], V[1], V[3]);  // C
  setFace(3, s.plane[3], V[1], V[0], D[0], D[1]);  // A
  setFace(4, s.plane[4], D[2], V[2], V[3], D[3]);  // Z
  setFace(5, vec4(0.0), D[0], D[2], D[3], D[1]);   // at infinity
  return dot(cross(s.vertex[2] - s.vertex[0], s.dir[2]), -s.plane[0].xyz) > 0.0 ? 1 : -1;
}

// Whether every triangle that emitPolyhedron draws runs around its face's outward normal the way
// `facing` says (the cross product of homogeneous corners, w >= 0, is that of the triangle, or of
// its limit where corners are at infinity). Not so where rounding leaves the polyhedron not quite
// convex: a thin wedge under a light that spans nearly a half-space (plane C's normal is then the
// sum of two almost opposite directions) can give a cap whose corners cross. Its outline is
// then no simple loop (default scene, 96 px: one edge's wedge covered a pixel three times).
bool orientedAsFacing(int faces) {
  for (int f = 0; f < faces; ++f) {
    int n = polyCount[f];
    if (f == 5 || n < 3 || outside(polyPlane[f]) >= 0.0) continue;
    vec4 p = polyCorner[f][0];
    float total = 0.0, inverted = 0.0;
    for (int k = 1; k + 1 < n; ++k) {
      vec4 q = polyCorner[f][k], r = polyCorner[f][k + 1];
      vec3 area = cross(p.xyz, q.xyz) * r.w + cross(q.xyz, r.xyz) * p.w + cross(r.xyz, p.xyz) * q.w;
      float a = float(facing) * dot(area, -polyPlane[f].xyz);
      total += abs(a);
      inverted = max(inverted, -a);
    }
    // A sliver triangle of rounding (a crossing next to a corner) may come out inverted; a
    // crossed polygon has an inverted triangle of its own size.
    if (inverted > 1e-3 * total) return false;
  }
  return true;
}

// Pyramid solid s the same way: faces 0-3 its sides, 4 its cap, 5 at infinity (face k lies
// between dir[k] and dir[k + 1], vertex[k] on faces k - 1, k and the cap). Face 0's triangle
// (V0, D1, D0) gives the facing from the directions alone.
int pyramidPolyhedron(DcsSolid s) {
  vec4 V[4], D[4];
  for (int k = 0; k < 4; ++k) {
    V[k] = vec4(s.vertex[k], 1.0);
    D[k] = vec4(s.dir[k], 0.0);
  }
  for (int k = 0; k < 4; ++k) setFace(k, s.plane[k], V[k], V[(k + 1) % 4], D[(k + 1) % 4], D[k]);
  setFace(4, s.plane[4], V[3], V[2], V[1], V[0]);
  setFace(5, vec4(0.0), D[0], D[1], D[2], D[3]);
  return dot(cross(s.dir[1], s.dir[0]), -s.plane[0].xyz) > 0.0 ? 1 : -1;
}

// The front faces of the polyhedron (faces whose plane has the eye outside; never the face at
// infinity), each a convex polygon as a zig-zag strip (whose facing is its polygon's); false when
// they would pass max_vertices or their outline cannot be trusted.
bool emitPolyhedron(int id, int faces) {
  if (!orientedAsFacing(faces)) return false;
  int total = 0;
  for (int f = 0; f < faces; ++f)
    if (f != 5 && polyCount[f] >= 3 && outside(polyPlane[f]) < 0.0) total += polyCount[f];
  if (total > POLY_EMITTED) return false;
  for (int f = 0; f < faces; ++f) {
    int n = polyCount[f];
    if (f == 5 || n < 3 || outside(polyPlane[f]) >= 0.0) continue;
    for (int k = 0; k < n; ++k) {  // 0, 1, n-1, 2, n-2, ...
      int j = (k & 1) == 1 ? (k + 1) / 2 : (n - k / 2) % n;
      emitVertex(id, clipFromWorld * polyCorner[f][j]);
    }
    EndPrimitive();
  }
  return true;
}

// The front faces of a wedge or pyramid solid (those whose plane has the eye outside), cut by
// the wedge's end planes and the view; false when the eye is inside the solid or within
// nearRadius of it.
bool emitSolid(int id, DcsEdge e, DcsSolid s) {
  facing = 0;
  float nearest = 1e30;
  for (int k = 0; k < 5; ++k) nearest = min(nearest, outside(s.plane[k]));
  vec4 side[DCS_SIDE_PLANES];
  int sides = 0;
#ifdef DCS_END_PLANES
  if (s.kind == DCS_SOLID_WEDGE) sides = dcsSidePlanes(e.v0.xyz, e.v1.xyz, side);
#endif
  for (int k = sides; k < DCS_SIDE_PLANES; ++k) side[k] = vec4(0.0);
  float nearestCut = nearest;
  for (int k = 0; k < sides; ++k) nearestCut = min(nearestCut, outside(side[k]));
  if (nearestCut >= -nearRadius) return false;
  // Tried in turn: cut by the end planes and the view, by the view, not at all. A cut fails
  // where its polygon does not close (rounding), or the faces would pass max_vertices. One call
  // site each: the functions are inlined, and the compile time grows with every copy.
  for (int attempt = 0; attempt < 3; ++attempt) {
    int ends = attempt == 0 ? sides : 0, cuts = ends + (attempt < 2 ? 4 : 0);
    // Without the end planes, the eye must be clear of the five planes by itself.
    if (attempt == 1 && nearest >= -nearRadius) return false;
    if (attempt == 1 && sides == 0) continue;  // the first attempt's cuts again
    facing = s.kind == DCS_SOLID_WEDGE ? wedgePolyhedron(s) : pyramidPolyhedron(s);
    bool cut = true;
    for (int k = 0; k < cuts && cut; ++k) {
      cut = cutPolyhedron(k < ends ? side[k] : viewPlane(k - ends), 6 + k);
      if (k >= ends) polyPlane[6 + k] = vec4(0.0);
    }
    if (cut && emitPolyhedron(id, 6 + cuts)) {
      PROFILE_COUNT(profWedgeEdges);
      return true;
    }
  }
  return false;
}

void main() {
  int id = vEdge[0];
  DcsEdge e = dcsEdges[id];
  if (!dcsSolidBegin(e)) return;
  DcsSolid s = dcsNoSolid();
  // A case whose solid the eye is too close to falls through to the next one.
  if (dcsSolidCase(1, e, s) && emitSolid(id, e, s)) return;
  if (dcsSolidCase(2, e, s) && emitSolid(id, e, s)) return;
  if (dcsSolidCase(3, e, s) && emitSolid(id, e, s)) return;
  emitRectangle(id, screenRectangle(e.v0.xyz, e.v1.xyz));
}
