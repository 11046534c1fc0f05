// Constants and small functions shared by C++ and GLSL. Valid in both languages: only
// #define, uint arithmetic with the `u` suffix, and functions written in the common subset.
// C++ includes it through src/sampling/shared.hpp (which provides `uint`); the shader loader
// prepends it to every shader. Never copy a value from here into either language by hand.
#ifndef PENUMBRA_SHARED_H
#define PENUMBRA_SHARED_H

// Functions here are `inline` in C++ (the header is included by several translation units).
// PENUMBRA_PRECISE: GLSL `precise` (no fused multiply-adds the compiler may choose differently
// in two shaders), nothing in C++.
#ifdef __cplusplus
#define PENUMBRA_FN inline
#define PENUMBRA_PRECISE
#else
#define PENUMBRA_FN
#define PENUMBRA_PRECISE precise
#endif

// ---- G-buffer layout (pipeline) ------------------------------------------------------------
#define PENUMBRA_GBUF_POSITION 0   // RGBA32F: world position, w = 1 where a surface was hit
#define PENUMBRA_GBUF_NORMAL 1     // RGBA32F: world normal facing the camera, w = material id
#define PENUMBRA_GBUF_ALBEDO 2     // RGBA16F: base colour, a = opacity
#define PENUMBRA_GBUF_SHADING 3    // RGBA32F: shading normal (interpolated vertex normal), unit, on
                                   // the side of the normal above; a = 0

// ---- texture units -------------------------------------------------------------------------
// Those every technique shares. A technique's own binding points are in its header beside its
// shaders (dcs_bindings.h, shadow_map_bindings.h, single_view_bindings.h), which its shaders and
// its C++ include.
#define PENUMBRA_UNIT_GBUF_POSITION 0
#define PENUMBRA_UNIT_GBUF_NORMAL 1
#define PENUMBRA_UNIT_GBUF_ALBEDO 2
#define PENUMBRA_UNIT_VISIBILITY 3      // RGBA16F: RGB visibility (eq. 2), a = 1
#define PENUMBRA_UNIT_SAMPLE_VIS 4      // R16F 2D array: per-sample transmittance, one layer a sample
#define PENUMBRA_UNIT_MATERIAL_TEX 5
#define PENUMBRA_UNIT_COUNTER 6         // R32F: shadow-volume count (hard-sv, dcs)
#define PENUMBRA_UNIT_FILTER_SOURCE 11  // RGBA32F: input of the interleaved-sampling filter
#define PENUMBRA_UNIT_GBUF_SHADING 20
#define PENUMBRA_IMAGE_SAMPLE_VIS 0     // image unit of the per-sample visibility array

// ---- shader storage / uniform buffer bindings ----------------------------------------------
// A graphics program (vertex/geometry/fragment) that writes a storage block declares storage
// blocks in that one stage only (gl::Program refuses others): Mesa 22.3's GLSL linker computes
// each stage's write mask with the program-wide block index, so with blocks in two stages the
// writing stage's block can be marked read-only, and zink then neither waits for its writes
// before a glGetBufferSubData nor orders them before later reads, which glMemoryBarrier
// guarantees (GL 4.5 7.12.2, BUFFER_UPDATE and SHADER_STORAGE barrier bits). Counters that
// several stages write are images (their write access is given at bind time).
#define PENUMBRA_SSBO_LIGHT_SAMPLES 0   // vec4 position (xyz), per set then sample
#define PENUMBRA_SSBO_SAMPLE_RADIANCE 1 // vec4 normalised luminance L_i (rgb) of eq. 2
#define PENUMBRA_VSSM_FIXED_ONE 32767.0 // vssm exact SAT: depth in [0,1] as 15-bit integers (sums of
                                        // squares stay below 2^53 at 2048^2: exact in doubles)

// ---- light shapes (match penumbra::LightShape) ---------------------------------------------
#define PENUMBRA_LIGHT_POINT 0
#define PENUMBRA_LIGHT_RECT 1
#define PENUMBRA_LIGHT_DISK 2
#define PENUMBRA_LIGHT_SPHERE 3

// ---- pixel patterns of light-sample sets (match penumbra::PixelPattern) --------------------
#define PENUMBRA_PATTERN_CORRELATED 0
#define PENUMBRA_PATTERN_DECORRELATED 1
#define PENUMBRA_PATTERN_INTERLEAVED 2

// ---- limits --------------------------------------------------------------------------------
#define PENUMBRA_MAX_SAMPLES 128
#define PENUMBRA_DCS_MAX_TARGETS 7      // packed counter targets per pass (+1 checksum = 8 MRT)
#define PENUMBRA_MAP_LOCAL_SIZE 64      // threads per work group of the point reprojection

// Integer hash (PCG output permutation); identical in C++ and GLSL.
PENUMBRA_FN uint penumbraHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// The light-sample set a pixel uses. Correlated: set 0 everywhere. Decorrelated: a hash of the
// pixel and seed picks one of `sets` rotated sets. Interleaved: the pixel's position in a K x K
// tile picks the set (sets == K*K).
PENUMBRA_FN uint penumbraSetForPixel(uint x, uint y, uint pattern, uint sets, uint k, uint seed) {
  if (pattern == uint(PENUMBRA_PATTERN_DECORRELATED))
    return penumbraHash(x ^ penumbraHash(y ^ penumbraHash(seed))) % sets;
  if (pattern == uint(PENUMBRA_PATTERN_INTERLEAVED)) return (y % k) * k + (x % k);
  return 0u;
}

// ---- dcs covered-sample modes (src/techniques/dcs/edge_lut.h) -------------------------------
#define PENUMBRA_DCS_COVERAGE_EXACT 0   // per-sample 3D test (common_dcs.glsl dcsCovered)
#define PENUMBRA_DCS_COVERAGE_NAIVE 1   // per-sample 2D test on 8-bit packed positions (paper 7.1)
#define PENUMBRA_DCS_COVERAGE_LUT 2     // sector & line bit fields from the edge LUT (paper 7.3)

// ---- dcs semi-opaque occluders (src/techniques/dcs/opacity.h) ------------------------------
#define PENUMBRA_DCS_OPACITY_OPAQUE 0   // one unit per occluder: visible iff the count is 0
#define PENUMBRA_DCS_OPACITY_SUM 1      // the paper's sum of opacities: T = 1 - Sat(count / Q)
#define PENUMBRA_DCS_OPACITY_PRODUCT 2  // units of -ln T: T = exp(-count * delta), 0 from U on

// Transmittance of a counter holding `count` units (negative counts read as 0); opaqueUnits is
// Q (sum) or U (product), unitLog is delta (product).
PENUMBRA_FN float penumbraDcsTransmittance(float count, int mode, float opaqueUnits, float unitLog) {
  float c = max(count, 0.0f);
  if (mode == PENUMBRA_DCS_OPACITY_SUM) return max(1.0f - c / opaqueUnits, 0.0f);
  if (mode == PENUMBRA_DCS_OPACITY_PRODUCT) return c >= opaqueUnits ? 0.0f : exp(-c * unitLog);
  return c > 0.0f ? 0.0f : 1.0f;
}

// How far off its surface visibility is evaluated for a point p, relative to p's own floating-
// point magnitude, never to the scene's size (Waechter and Binder, "A Fast and Robust Method for
// Avoiding Self-Intersection", Ray Tracing Gems 2019, ch. 6: an offset of 256 ULPs of the point's
// coordinates, a fixed tiny offset near the origin). We use the largest coordinate for all three
// axes (one distance along the view ray below, not one integer offset per axis) and keep their
// constants: 256 ULPs = 2^-15 relative, magnitudes below 1/32 count as 1/32. Points are in
// camera-relative coordinates (Scene::cameraRelative), so the magnitude is the distance to the
// camera (at least zNear) and a scene translated anywhere gives the same offset; a scaled scene
// gets a scaled offset; a mirrored one the same (absolute values).
#define PENUMBRA_EPS_RELATIVE (1.0f / 32768.0f)
#define PENUMBRA_EPS_ORIGIN (1.0f / 32.0f)
PENUMBRA_FN float penumbraSurfaceEpsilon(vec3 p) {
  float m = max(max(abs(p.x), abs(p.y)), max(abs(p.z), PENUMBRA_EPS_ORIGIN));
  return m * PENUMBRA_EPS_RELATIVE;
}

// Where visibility is evaluated for a visible point p (unit normal n facing the camera, camera
// at `eye`): p moved towards the camera along the view ray until it is penumbraSurfaceEpsilon(p)
// off its surface, at most PENUMBRA_ORIGIN_MAX_STRETCH times that along the ray (grazing views).
// The reference starts its shadow rays there, and the shadow-volume count and the dcs wedges
// evaluate their plane tests there: on the view ray, so that what the rasteriser found along
// that ray (which volume face the ray meets, near a face's border too) holds for the point (an
// origin moved along the normal instead left a pixel of hard case 19 off by one, where the ray
// passes within 1e-5 of the box's bottom edge). Without a camera (CPU-only G-buffers),
// eye = p + n.
#define PENUMBRA_ORIGIN_MAX_STRETCH 16.0f
PENUMBRA_FN vec3 penumbraShadowOrigin(vec3 p, vec3 n, vec3 eye) {
  PENUMBRA_PRECISE vec3 v = normalize(eye - p);
  PENUMBRA_PRECISE float along = penumbraSurfaceEpsilon(p) / max(dot(n, v), 1.0f / PENUMBRA_ORIGIN_MAX_STRETCH);
  PENUMBRA_PRECISE vec3 o = p + v * along;
  return o;
}

#endif
