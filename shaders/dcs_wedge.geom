// The screen footprint of an edge's wedge: every pixel whose point p can have e between itself
// and some point of the light. Those points lie in conv({v0, v1}) + cone{v_i - x_j}, with x_j the
// corners of a convex polytope around the light (rect: 4, disk: its square, sphere: a cube), so
// their projection lies in the bounding rectangle of the projected v_i and of the vanishing points
// of the directions v_i - x_j; when a direction points behind the camera the footprint is the
// whole screen. A rectangle covers each pixel exactly once, which the exact per-fragment
// integration needs; the paper's outer/inner half-wedge strips (Fig. 7) are tighter but can
// overlap in screen space, and the per-fragment sign makes the outer/inner split unnecessary.
#include "common_dcs.glsl"

layout(points) in;
layout(triangle_strip, max_vertices = 4) out;

uniform mat4 clipFromWorld;
uniform vec3 lightCorners[8];
uniform int lightCornerCount;

flat in int vEdge[];
flat out int gEdge;

void grow(vec4 q, inout vec2 lo, inout vec2 hi, inout bool full) {
  if (q.w <= 1e-7 * (abs(q.x) + abs(q.y))) { full = true; return; }
  vec2 ndc = q.xy / q.w;
  lo = min(lo, ndc);
  hi = max(hi, ndc);
}

void main() {
  int id = vEdge[0];
  vec3 a = dcsEdges[id].v0.xyz;
  vec3 b = dcsEdges[id].v1.xyz;
  vec2 lo = vec2(1e30), hi = vec2(-1e30);
  bool full = false;
  grow(clipFromWorld * vec4(a, 1.0), lo, hi, full);
  grow(clipFromWorld * vec4(b, 1.0), lo, hi, full);
  for (int j = 0; j < lightCornerCount; ++j) {
    grow(clipFromWorld * vec4(a - lightCorners[j], 0.0), lo, hi, full);
    grow(clipFromWorld * vec4(b - lightCorners[j], 0.0), lo, hi, full);
  }
  if (full) { lo = vec2(-1.0); hi = vec2(1.0); }
  lo = max(lo, vec2(-1.0));
  hi = min(hi, vec2(1.0));
  if (lo.x >= hi.x || lo.y >= hi.y) return;
  gEdge = id; gl_Position = vec4(lo.x, lo.y, 0.5, 1.0); EmitVertex();
  gEdge = id; gl_Position = vec4(hi.x, lo.y, 0.5, 1.0); EmitVertex();
  gEdge = id; gl_Position = vec4(lo.x, hi.y, 0.5, 1.0); EmitVertex();
  gEdge = id; gl_Position = vec4(hi.x, hi.y, 0.5, 1.0); EmitVertex();
  EndPrimitive();
}
