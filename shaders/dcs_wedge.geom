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
#include "dcs_solid.glsl"

layout(points) in;
layout(triangle_strip, max_vertices = 20) out;

uniform vec3 eyePosition;
uniform float nearRadius;  // the largest distance from the eye to a point of the near plane window

flat in int vEdge[];
flat out int gEdge;

void emitVertex(int id, vec4 position) {
  gEdge = id;
  gl_Position = position;
  EmitVertex();
}

void emitQuad(int id, vec4 p0, vec4 p1, vec4 p2, vec4 p3) {  // strip order
  emitVertex(id, p0);
  emitVertex(id, p1);
  emitVertex(id, p2);
  emitVertex(id, p3);
  EndPrimitive();
}

// Drawn at the near plane (depth 1) so that the depth test keeps every pixel.
void emitRectangle(int id, vec4 r) {
  PROFILE_COUNT(profRectangleEdges);
  if (r.x >= r.z || r.y >= r.w) return;
  emitVertex(id, vec4(r.x, r.y, 1.0, 1.0));
  emitVertex(id, vec4(r.z, r.y, 1.0, 1.0));
  emitVertex(id, vec4(r.x, r.w, 1.0, 1.0));
  emitVertex(id, vec4(r.z, r.w, 1.0, 1.0));
  EndPrimitive();
}

float outside(vec4 plane) { return dot(plane.xyz, eyePosition) - plane.w; }  // < 0: eye outside

// The front faces of a wedge or pyramid solid (those whose plane has the eye outside); false
// when the eye is inside the solid or within nearRadius of it.
bool emitSolid(int id, DcsSolid s) {
  float h[5];
  float nearest = 1e30;
  for (int k = 0; k < 5; ++k) {
    h[k] = outside(s.plane[k]);
    nearest = min(nearest, h[k]);
  }
  if (nearest >= -nearRadius) return false;
  PROFILE_COUNT(profWedgeEdges);
  vec4 V[4], D[4];
  for (int k = 0; k < 4; ++k) {
    V[k] = clipFromWorld * vec4(s.vertex[k], 1.0);
    D[k] = clipFromWorld * vec4(s.dir[k], 0.0);
  }
  if (s.kind == DCS_SOLID_WEDGE) {  // F, B, C, A, Z
    if (h[0] < 0.0) emitQuad(id, V[0], V[2], D[0], D[2]);
    if (h[1] < 0.0) emitQuad(id, V[1], V[3], D[1], D[3]);
    if (h[2] < 0.0) emitQuad(id, V[0], V[2], V[1], V[3]);
    if (h[3] < 0.0) emitQuad(id, V[0], V[1], D[0], D[1]);
    if (h[4] < 0.0) emitQuad(id, V[2], V[3], D[2], D[3]);
  } else {  // the four faces, the cap
    for (int k = 0; k < 4; ++k)
      if (h[k] < 0.0) emitQuad(id, V[k], V[(k + 1) % 4], D[k], D[(k + 1) % 4]);
    if (h[4] < 0.0) emitQuad(id, V[0], V[1], V[3], V[2]);
  }
  return true;
}

void main() {
  int id = vEdge[0];
  DcsEdge e = dcsEdges[id];
  if (!dcsSolidBegin(e)) return;
  DcsSolid s = dcsNoSolid();
  // A case whose solid the eye is too close to falls through to the next one.
  if (dcsSolidCase(1, e, s) && emitSolid(id, s)) return;
  if (dcsSolidCase(2, e, s) && emitSolid(id, s)) return;
  if (dcsSolidCase(3, e, s) && emitSolid(id, s)) return;
  emitRectangle(id, screenRectangle(e.v0.xyz, e.v1.xyz));
}
