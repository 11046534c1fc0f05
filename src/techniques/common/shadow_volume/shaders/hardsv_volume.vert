// Shadow-volume count: a point of a face's cover in window coordinates (volume_cover.h) and the
// face it covers. The context's glClipControl(GL_UPPER_LEFT) turns y over.
layout(location = 0) in vec2 inPixel;
layout(location = 1) in uint inFace;
uniform vec2 viewport;
flat out uint vFace;
void main() {
  vec2 ndc = inPixel / viewport * 2.0 - 1.0;
  gl_Position = vec4(ndc.x, -ndc.y, 0.0, 1.0);
  vFace = inFace;
}
