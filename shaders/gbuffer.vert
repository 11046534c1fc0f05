// G-buffer pass: world position, face normal and uv of the nearest surface.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;  // geometric (face) normal
layout(location = 2) in vec2 inUv;

uniform mat4 clipFromWorld;

out vec3 vPosition;
out vec3 vNormal;
out vec2 vUv;

invariant gl_Position;

void main() {
  vPosition = inPosition;
  vNormal = inNormal;
  vUv = inUv;
  gl_Position = clipFromWorld * vec4(inPosition, 1.0);
}
