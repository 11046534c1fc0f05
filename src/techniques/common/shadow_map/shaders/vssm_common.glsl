// vssm's and msm's normalised depth (src/techniques/vssm, msm): view depth mapped to [0, 1] over
// [depthMin, depthMax] (the nearest occluder to the scene's far end); an empty map texel
// (reversed depth 0, infinitely far) is 1. `near` is the map's near plane (z = near / d).
uniform float depthMin, depthMax;
float normalisedDepth(float d) { return clamp((d - depthMin) / (depthMax - depthMin), 0.0, 1.0); }
float viewDepth(float x) { return depthMin + x * (depthMax - depthMin); }
float normalisedMapDepth(float z, float near) { return z > 0.0 ? normalisedDepth(near / z) : 1.0; }
