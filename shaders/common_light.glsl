// The light and its sample sets, as the pipeline binds them for visibility resolves and shading.
#include "sampling/shaders/sample_sets.h"
uniform int lightShape;         // PENUMBRA_LIGHT_*
uniform vec3 lightPosition;     // centre
uniform vec3 lightNormal;       // emission normal of one-sided lights, 0 for isotropic ones
uniform vec3 lightTangent;      // rect and disk: the frame's tangent (bitangent = normal x tangent)
uniform vec2 lightHalfExtent;     // rect: half width and height along tangent and bitangent
uniform float lightShapeRadius; // disk and sphere: the radius
uniform int lightTextured;      // 1: an emission texture modulates the light
uniform vec3 lightEmission;     // colour * intensity
uniform float lightScale;       // area (rect, disk), pi R^2 (sphere), 1 (point): eq. 3 power
uniform float sampleWeight;     // LightSampleSet::sampleWeight (eq. 6)
uniform uint samplePattern;     // PENUMBRA_PATTERN_*
uniform uint sampleSets;        // number of sets
uniform uint sampleK;           // interleave K
uniform uint sampleSeed;

// N is read from the sample buffer, not a uniform: the loops over a pixel's samples are bounded
// by it, and Mesa 22.3's lavapipe (under zink) compiles a new shader, never freed, at every draw
// of a program whose loop bounds are uniforms (common_dcs_pass.glsl).
layout(std430, binding = PENUMBRA_SSBO_LIGHT_SAMPLES) readonly buffer LightSamples {
  uint sampleCount;        // N (renderer.cpp sampleBufferOf)
  uint sampleHeaderPad[3];
  vec4 samplePositions[];  // [set * N + k], xyz world
};
layout(std430, binding = PENUMBRA_SSBO_SAMPLE_RADIANCE) readonly buffer SampleLuminance {
  vec4 sampleLuminance[];  // L_i of eq. 2, rgb
};

uint pixelSampleBase(ivec2 pixel) {
  return penumbraSetForPixel(uint(pixel.x), uint(pixel.y), samplePattern, sampleSets, sampleK,
                             sampleSeed) * sampleCount;
}

// Horizon rule shared with the reference: a sample below the surface's tangent plane is not
// seen (docs/architecture.md "Conventions").
bool aboveHorizon(vec3 p, vec3 n, vec3 x) { return dot(n, x - p) > 0.0; }
