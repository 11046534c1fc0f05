// mvr, layered: passes each triangle to the map layer of its instance (gl_in[] indexed by
// constants only: a non-constant index is a known Mesa crash, hard-cases.md).
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
flat in int vLayer[];
flat out int gLayer;  // for fragment shaders that need it (shadow_map_transmittance.frag)
in vec2 vUv[];
out vec2 gUv;  // the alpha test's (shading/shaders/alpha_test_depth.glsl)
void main() {
  gl_Layer = vLayer[0];
  gLayer = vLayer[0];
  gUv = vUv[0];
  gl_Position = gl_in[0].gl_Position;
  EmitVertex();
  gl_Layer = vLayer[0];
  gLayer = vLayer[0];
  gUv = vUv[1];
  gl_Position = gl_in[1].gl_Position;
  EmitVertex();
  gl_Layer = vLayer[0];
  gLayer = vLayer[0];
  gUv = vUv[2];
  gl_Position = gl_in[2].gl_Position;
  EmitVertex();
  EndPrimitive();
}
