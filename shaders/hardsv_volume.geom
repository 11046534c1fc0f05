// Z-fail shadow volumes (Everitt & Kilgard 2002) extruded to infinity from the light centre,
// for the per-triangle volumes described in geometry/silhouette.h.
// SIDES: input lines (a, b) ordered on the CPU so that the quad (b, a, a_inf, b_inf) faces out
//   of the volume; weight = |m_e|. CAPS: input triangles oriented to face the light (near cap);
//   the far cap is the same triangle projected to infinity, reversed.
// Points at infinity are homogeneous (direction from the light, w = 0); with the reversed-Z
// infinite projection they land on depth 0 and are never clipped (depth clamp covers the near
// plane, hard cases 2, 3, 19).
uniform mat4 clipFromWorld;
uniform vec3 lightPosition;

#ifdef SIDES
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
#else
layout(triangles) in;
layout(triangle_strip, max_vertices = 6) out;
#endif

in vec4 vPositionWeight[];
flat out float gWeight;

vec4 nearPoint(vec3 p) { return clipFromWorld * vec4(p, 1.0); }
vec4 farPoint(vec3 p) { return clipFromWorld * vec4(p - lightPosition, 0.0); }

void emit(vec4 clip, float w) {
  gl_Position = clip;
  gWeight = w;
  EmitVertex();
}

void main() {
  float w = vPositionWeight[0].w;
  // gl_in / array inputs indexed by constants only (non-constant indexing crashes Mesa).
  vec3 a = vPositionWeight[0].xyz;
  vec3 b = vPositionWeight[1].xyz;
#ifdef SIDES
  emit(nearPoint(b), w);
  emit(nearPoint(a), w);
  emit(farPoint(b), w);
  emit(farPoint(a), w);
  EndPrimitive();
#else
  vec3 c = vPositionWeight[2].xyz;
  emit(nearPoint(a), w);
  emit(nearPoint(b), w);
  emit(nearPoint(c), w);
  EndPrimitive();
  emit(farPoint(a), w);
  emit(farPoint(c), w);
  emit(farPoint(b), w);
  EndPrimitive();
#endif
}
