// Z-fail count into a float target by additive blending (not the 8-bit stencil, which wraps):
// only volume fragments behind the visible surface pass the depth test; leaving the volume
// (back face towards the camera) adds the weight, entering it subtracts. The sum is the
// winding number of the visible point, i.e. the number of volumes containing it.
flat in float gWeight;
out float outCount;
void main() { outCount = gl_FrontFacing ? -gWeight : gWeight; }
