// Z-fail shadow volumes (Everitt & Kilgard 2002) extruded to infinity from the light centre,
// for the per-triangle volumes described in geometry/silhouette.h.
// SIDES: input lines (v0, v1) in the edge's own order (the order dcs's edge buffer has, so that
//   both compute the same plane test, common_volume.glsl); weight = m_e, whose
//   sign says which way the quad faces out of the volume. CAPS: input triangles oriented to face
//   the light (near cap); the far cap is the same triangle projected to infinity, reversed.
// Points at infinity are homogeneous (direction from the light, w = 0); with the reversed-Z
// infinite projection they land on depth 0 and are never clipped (depth clamp covers the near
// plane, hard cases 2, 3, 19).
// The fragment shader decides "behind the visible point" with a plane test, not the depth
// buffer (hardsv_volume.frag); the geometry shader hands it the face's plane data.
#include "common_volume.glsl"

uniform mat4 clipFromWorld;
uniform vec3 lightPosition;
uniform vec3 eyePosition;

#ifdef SIDES
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
flat out vec3 gEdgeV0, gEdgeV1;
#else
layout(triangles) in;
layout(triangle_strip, max_vertices = 6) out;
flat out vec4 gPlane;  // near cap: the triangle's plane (n, -n.a); far cap: w = 0, n = 0
#endif

in vec4 vPositionWeight[];
flat out float gWeight;
flat out int gEyeSide;  // which side of the face's plane the camera is on (+1 / -1), 0: far cap

vec4 nearPoint(vec3 p) { return clipFromWorld * vec4(p, 1.0); }
vec4 farPoint(vec3 p) { return clipFromWorld * vec4(p - lightPosition, 0.0); }

void emit(vec4 clip, float w, int eyeSide) {
  gl_Position = clip;
  gWeight = w;
  gEyeSide = eyeSide;
  EmitVertex();
}

void main() {
  float w = abs(vPositionWeight[0].w);
  // gl_in / array inputs indexed by constants only (non-constant indexing crashes Mesa).
  vec3 a = vPositionWeight[0].xyz;
  vec3 b = vPositionWeight[1].xyz;
#ifdef SIDES
  gEdgeV0 = a;
  gEdgeV1 = b;
  int eyeSide = sideOfEdgePlane(a, b, lightPosition, eyePosition);
  // m > 0: the effective near cap runs v0 -> v1, so the outward side quad runs v1 -> v0.
  if (vPositionWeight[0].w < 0.0) {
    vec3 t = a;
    a = b;
    b = t;
  }
  emit(nearPoint(b), w, eyeSide);
  emit(nearPoint(a), w, eyeSide);
  emit(farPoint(b), w, eyeSide);
  emit(farPoint(a), w, eyeSide);
  EndPrimitive();
#else
  vec3 c = vPositionWeight[2].xyz;
  vec3 n = cross(b - a, c - a);
  gPlane = vec4(n, -dot(n, a));
  int eyeSide = dot(n, eyePosition) + gPlane.w >= 0.0 ? 1 : -1;
  emit(nearPoint(a), w, eyeSide);
  emit(nearPoint(b), w, eyeSide);
  emit(nearPoint(c), w, eyeSide);
  EndPrimitive();
  gPlane = vec4(0.0);
  emit(farPoint(a), w, 0);
  emit(farPoint(c), w, 0);
  emit(farPoint(b), w, 0);
  EndPrimitive();
#endif
}
