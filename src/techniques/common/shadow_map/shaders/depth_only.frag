// Depth-only passes (multi-view depth maps, the reproject central map): the depth test writes,
// where an alpha-tested occluder is present (shading/shaders/alpha_test_depth.glsl).
#include "shading/shaders/alpha_test_depth.glsl"
void main() { penumbraAlphaDiscard(); }
