// The ground floor: the binding points, limits and enums shared by C++ and GLSL, the same
// values in both languages; nothing else (the functions both compile live beside the code that
// owns them: shared/numerics.h, sampling/shaders/, shading/shaders/, a technique's shaders/).
// Valid in both languages: only #define and the macros below. The shader loader prepends this
// file to every stage; C++ includes it through shared/shared.hpp (penumbra_shared, the bottom
// layer), and a static_assert beside each C++ enum checks that its values match. Never copy a
// value from here into either language by hand.
#ifndef PENUMBRA_SHARED_H
#define PENUMBRA_SHARED_H

// Functions in the GLSL-shared headers are `inline` in C++ (included by several translation
// units). PENUMBRA_PRECISE: GLSL `precise` (no fused multiply-adds the compiler may choose
// differently in two shaders), nothing in C++. PENUMBRA_INOUT / PENUMBRA_OUT: a reference
// parameter in C++, inout / out in GLSL.
#ifdef __cplusplus
#define PENUMBRA_FN inline
#define PENUMBRA_PRECISE
#define PENUMBRA_INOUT(T) T&
#define PENUMBRA_OUT(T) T&
#else
#define PENUMBRA_FN
#define PENUMBRA_PRECISE precise
#define PENUMBRA_INOUT(T) inout T
#define PENUMBRA_OUT(T) out T
#endif

// ---- G-buffer layout (pipeline) ------------------------------------------------------------
#define PENUMBRA_GBUF_POSITION 0   // RGBA32F: world position, w = 1 where a surface was hit
#define PENUMBRA_GBUF_NORMAL 1     // RGBA32F: world normal facing the camera, w = material id
#define PENUMBRA_GBUF_ALBEDO 2     // RGBA16F: base colour, a = opacity
#define PENUMBRA_GBUF_SHADING 3    // RGBA32F: shading normal (interpolated vertex normal), unit, on
                                   // the side of the normal above; a = 0
#define PENUMBRA_GBUF_MATERIAL 4   // RGBA16F: metallic, roughness, BRDF model (PENUMBRA_BRDF_*), 0

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
#define PENUMBRA_UNIT_GBUF_MATERIAL 21
#define PENUMBRA_UNIT_MATERIAL_MR_TEX 22 // glTF metallicRoughnessTexture (G roughness, B metallic)
#define PENUMBRA_UNIT_LTC 23            // RGBA32F 2D array: the LTC GGX table (luts/ltc_ggx.lut)
#define PENUMBRA_UNIT_LIGHT_PREFILTERED 24  // RGBA32F 2D array: a textured light's prefiltered emission
#define PENUMBRA_UNIT_UNSHADOWED 25     // RGBA32F: ratio-exact's unshadowed term of one light (CPU integral)
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
#define PENUMBRA_SSBO_VOLUME_FACES 8    // shadow-volume count (hard-sv, dcs): 3 vec4 a face (hardsv_volume.frag)

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

// ---- BRDF models (match penumbra::BrdfModel; the BRDF is shading/shaders/shading.h) ----------
#define PENUMBRA_BRDF_LAMBERT 0
#define PENUMBRA_BRDF_METALLIC_ROUGHNESS 1

#endif
