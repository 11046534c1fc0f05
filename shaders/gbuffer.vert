// G-buffer pass: world position, face normal and uv of the nearest surface.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;  // geometric (face) normal, unit
layout(location = 2) in vec2 inUv;
layout(location = 3) in float inPlane;  // dot(face normal, a vertex), in double on the CPU
layout(location = 4) in vec3 inShading;  // the corner's shading normal (vertex normal, unit)

uniform mat4 clipFromWorld;

out vec3 vPosition;
out vec3 vNormal;
out vec2 vUv;
out vec3 vShading;
flat out float vPlane;

invariant gl_Position;

void main() {
  vPosition = inPosition;
  vNormal = inNormal;
  vUv = inUv;
  vShading = inShading;
  vPlane = inPlane;
  gl_Position = clipFromWorld * vec4(inPosition, 1.0);
}
