// The one lighting pipeline (deferred): G-buffer, then per light a visibility stage supplied by
// a Technique, then shading; several lights add into a linear HDR image.
//
// Shading modes (DCS paper section 6):
//  * Modulate (eq. 3): the light is shaded as a point at its centre carrying the whole light's
//    power, multiplied by the RGB visibility buffer of eq. 2.
//  * PerSample (eq. 6): the sum over light samples of the direct illumination of each sample,
//    with each sample's transmittance; needs a technique that provides per-sample results.
//  * Ratio (Heitz, Hill and McGuire 2018, "Combining analytic direct illumination and
//    stochastic shadows"), the default: the unshadowed term U, whose diffuse part is in closed
//    form for untextured rect, disk and sphere lights (shading/shaders/shading.h penumbraLightPolygon,
//    penumbraBallIrradiance) and whose GGX specular part is the LTC integral for untextured rect
//    and disk lights (shading/ltc.h, the table built in from luts/ltc_ggx.lut); for textured
//    rect and disk lights both are those integrals times the emission prefiltered for each lobe
//    (Heitz et al. 2016 section 5.3, shading/prefiltered_light.h); else (sphere lights' LTC,
//    textured spheres, points) the unshadowed sum over the pixel's samples; times the shadow ratio sum_k w_k T_k /
//    sum_k w_k, w_k = f L_k cos cos / r^2 of sample k, from the per-sample results, or V / V_unshadowed (eq. 2 over its
//    unshadowed value) for techniques that give only V.
// All use the material's BRDF (shading/shaders/shading.h penumbraBrdf), the same function the reference uses.
#pragma once

#include <map>
#include <set>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "core/names.h"
#include "core/timer.h"
#include "gl/context.h"
#include "gl/objects.h"
#include "gl/statistics.h"
#include "pipeline/technique.h"
#include "sampling/light_samples.h"
#include "scene/scene.h"

namespace penumbra {

class Enclosures;

// RatioExact: Ratio with the unshadowed term integrated on the CPU (shading/light_integral.h:
// MIS of light and BRDF samples, transmittance 1, to a 1e-3 relative standard error) in place
// of the closed forms and the LTC: slow, but no measurement then depends on the LTC's fit.
enum class ShadingMode { Modulate, PerSample, Ratio, RatioExact };
inline constexpr Named<ShadingMode> kShadingModeNames[] = {{ShadingMode::Ratio, "ratio"},
                                                           {ShadingMode::RatioExact, "ratio-exact"},
                                                           {ShadingMode::Modulate, "modulate"},
                                                           {ShadingMode::PerSample, "per-sample"}};
inline const char* toString(ShadingMode m) { return nameOf(kShadingModeNames, m); }

struct RenderSettings {
  int width = 256, height = 256;
  SamplingParams sampling;
  float time = 0.0f;
  // Ratio (Heitz, Hill and McGuire 2018) by default: the lowest shaded error against the converged
  // reference of the three on the shipped scenes (docs/results/shading-modes.md).
  ShadingMode shading = ShadingMode::Ratio;
  // Per-sample visibility of techniques that have it, read back into LightResult::perSample for
  // comparisons. Off (benchmarks), it is produced only when per-sample shading needs it.
  bool perSampleResults = true;
  // Interleaved sampling (PixelPattern::Interleaved, K > 1): the normal/depth-aware K x K gather
  // of shaders/pipeline_filter.frag on the visibility buffer (and, for eq. 6, on each light's
  // shaded contribution). Per-sample results stay unfiltered.
  bool interleaveFilter = true;
  // The largest vertex buffer GpuScene makes; a bigger scene is split into several buffers
  // (one draw per buffer and material). GL sizes and offsets are GLsizei/GLint (2^31 - 1) and
  // llvmpipe's vertex fetch crashed on a 2.1 GiB buffer, so the default
  // stays far below; tests set it small to exercise the split.
  std::size_t maxVertexBufferBytes = std::size_t(256) << 20;
  // The G-buffer read back into FrameResult::gbuffer every frame (harness time, stage "gbuffer
  // readback"); off, only a technique that reads it on the CPU (raytrace) pays for it.
  bool gbufferResults = true;
  // Per stage, the GL's pipeline statistics (StageTime::counts) where the GL has them
  // (gl::PipelineStatistics::supported()).
  bool pipelineStatistics = true;
  // Lights a closed opaque mesh separates from everything the camera sees are culled for the
  // techniques that ask for it (Technique::cullsSeparatedLights, pipeline/enclosure.h). Off:
  // those techniques' own answer (tests of what they do inside closed meshes).
  bool cullSeparatedLights = true;
};

struct LightResult {
  Image visibility;              // RGB, eq. 2
  std::vector<float> perSample;  // [pixel * N + k] transmittance, empty if not provided
  int samples = 0;
  // Per sample k of a rect light with one sample set (correlated pattern): its distance from the
  // light's centre in half-sides, max(|2u - 1|, |2v - 1|) in [0, 1]; empty otherwise. What the
  // per-sample agreement by ring (compare/measure.h) bins by.
  std::vector<float> sampleRadius;
  std::vector<std::uint8_t> unshadowed;  // Technique::unshadowedPixels() for this light
  Image visibilityVariance;              // a technique's own noise (CpuShading::visibilityVariance); empty: none
};

struct FrameResult {
  Image color;  // RGB linear radiance
  // The variance of each pixel of `color` as estimated by a technique that shades its lights
  // itself and knows its own noise (the converged reference); empty: none.
  Image colorVariance;
  std::vector<LightResult> lights;
  CpuGBuffer gbuffer;           // empty unless RenderSettings::gbufferResults or the technique read it
  StageTimer timer;             // the technique's stages and, apart (StageKind::Harness), the harness's
  std::size_t memoryBytes = 0;  // pipeline + technique render targets
  std::vector<std::pair<std::string, double>> statistics;  // Technique::statistics()
  // What the frame models differently from the reference, one line each (compare puts them in
  // the technique's row): an approximation it makes on this scene, not an error.
  std::vector<std::string> notes;
};

// Geometry uploaded once per scene, the camera, and the G-buffer for one output size.
class GpuScene {
 public:
  // maxVertexBufferBytes: see RenderSettings.
  GpuScene(const Scene& scene, int width, int height,
           std::size_t maxVertexBufferBytes = RenderSettings{}.maxVertexBufferBytes);

  int width() const { return width_; }
  int height() const { return height_; }
  // Camera: reversed-Z infinite perspective (depth 1 at the near plane, 0 at infinity).
  const glm::mat4& clipFromWorld() const { return clipFromWorld_; }
  const glm::vec3& cameraPosition() const { return cameraPos_; }

  // Draws every triangle of the scene (G-buffer layout: position, face normal, uv, plane
  // offset, shading normal).
  void drawGBuffer(const gl::Program& program) const;
  void renderGBuffer();  // fills the G-buffer textures below
  // Draws triangles (attribute 0: position, 2: uv) `instances` times with `program` (in use):
  // for passes that only need occluder geometry (depth maps, point generation). Opaque:
  // materials of opacity 1, alpha-tested ones (Scene::alphaTested) with `program`'s alpha test
  // (shading/shaders/alpha_test_depth.glsl: its uniforms set and the texture bound per draw; a
  // program without it is a programmer error when the scene has such materials); SemiOpaque:
  // opacity in (0, 1), with `program`'s uniform "opacity" set per draw. Fully transparent
  // materials (opacity 0) occlude nothing and are never drawn.
  enum class Occluders { Opaque, SemiOpaque };
  void drawTriangles(GLsizei instances, Occluders which, const gl::Program& program) const;
  bool hasAlphaTested() const { return hasAlphaTested_; }
  const gl::Texture& position() const { return position_; }
  const gl::Texture& normal() const { return normal_; }
  const gl::Texture& albedo() const { return albedo_; }
  const gl::Texture& shadingNormal() const { return shading_; }
  const gl::Texture& depth() const { return depth_; }
  void bindGBuffer() const;  // to the PENUMBRA_UNIT_GBUF_* units
  CpuGBuffer readGBuffer() const;
  std::size_t memoryBytes() const;

 private:
  // The alpha test's uniforms of `program` for a draw of `material` (off unless alpha-tested).
  void setAlphaTest(const gl::Program& program, int material) const;
  // One vertex buffer of at most maxVertexBufferBytes and its vertex array.
  struct Chunk {
    gl::Buffer vertices;
    gl::VertexArray vao;
    GLsizei count = 0;
  };
  // The part of a mesh in one chunk.
  struct Draw {
    int chunk;
    GLint first;
    GLsizei count;
    int material;
  };
  const Scene& scene_;
  int width_, height_;
  glm::mat4 clipFromWorld_;
  glm::vec3 cameraPos_;
  std::vector<Chunk> chunks_;
  std::vector<Draw> draws_;
  std::vector<std::uint8_t> alphaTested_;      // per material: Scene::alphaTested
  bool hasAlphaTested_ = false;                // a draw of an alpha-tested material
  bool allOpaque_ = true;                      // every material of opacity 1: one draw covers every (opaque) occluder
  std::vector<gl::Texture> materialTextures_;  // parallel to scene.textures
  gl::Texture position_, normal_, albedo_, shading_, material_, depth_;
  gl::Framebuffer fbo_;
  gl::Program program_;
};

// Renders frames of one scene with one technique, in `context` (current). Techniques and the
// reference see the scene in camera-relative coordinates (Scene::makeCameraRelative): a scene
// not yet in them is copied and translated once here.
class Renderer {
 public:
  Renderer(gl::Context& context, const Scene& scene, const RenderSettings& settings);
  ~Renderer();

  // Renders one frame. Throws penumbra::Error for settings the technique cannot honour (e.g.
  // per-sample shading with a technique that has no per-sample results), and, naming `name`,
  // when a visibility buffer or the shaded image holds a NaN or an infinity (never an image
  // that is silently wrong).
  FrameResult render(Technique& technique, const std::string& name = "technique");

 private:
  // A frame's steps (renderer.cpp): per light, renderLight's visibility, interleaving filter,
  // shading and read-back; then finishFrame.
  struct FrameState;
  struct LightState;
  FrameResult renderFrame(Technique& technique, const std::string& name);
  void renderLight(FrameState& frame, std::size_t lightIndex);
  void renderVisibility(FrameState& frame, LightState& light);
  void filterVisibility(FrameState& frame, LightState& light);
  void drawInterleaveFilter(const gl::Texture& source, int interleaveK);
  void addOwnShading(FrameState& frame, LightState& light);
  void shadeLight(FrameState& frame, LightState& light);
  void readBackLight(FrameState& frame, LightState& light);
  FrameResult finishFrame(FrameState& frame);
  std::unique_ptr<Scene> local_;  // a camera-relative copy, when the scene given was not
  const Scene& scene_;            // the scene every technique renders: camera at the origin
  RenderSettings settings_;
  std::unique_ptr<GpuScene> gpu_;
  gl::Texture color_, visibility_, perSample_;
  gl::Texture filtered_, lightColor_;  // interleaved sampling: filtered visibility, eq. 6 light term
  gl::Framebuffer colorFbo_, filteredFbo_, lightColorFbo_;
  gl::Texture exactUnshadowed_;  // ratio-exact: one light's unshadowed term
  gl::Texture ltc_;              // ratio shading: the LTC GGX table (shading/ltc.h), two layers, linear filtering
  // Ratio shading: textured rect and disk lights' prefiltered emission (shading/prefiltered_light.h),
  // one layer a level, by emission texture and support (disk or not); made on first use.
  struct Prefiltered {
    gl::Texture texture;
    float sigma0 = 0.0f;
    int levels = 0;
  };
  std::map<std::pair<const Image*, bool>, Prefiltered> prefiltered_;
  const Prefiltered* prefilteredFor(const Light& light);
  gl::Program shade_, filter_;  // shade_: pipeline_shade.frag for settings.shading
  gl::VertexArray emptyVao_;
  std::uint64_t prepared_ = 0;                              // Technique::serial() of the technique prepared last
  std::unique_ptr<Enclosures> enclosures_;                  // made when a technique culls lights (pipeline/enclosure.h)
  std::set<std::pair<std::uint64_t, std::size_t>> warned_;  // (technique, light) named as straddling
  std::unique_ptr<gl::PipelineStatistics> statistics_;      // null where the GL has none
};

// Camera matrices shared by the pipeline and the reference (so both see the same pixels).
glm::mat4 viewFromWorld(const Camera& camera);
glm::mat4 clipFromViewReversedInfinite(const Camera& camera, float aspect);

}  // namespace penumbra

namespace penumbra {
// Sets the uniforms of shaders/common_light.glsl on `program` for `light` and its samples. The
// sample buffers themselves are bound by the pipeline before each light's visibility stage.
void setLightUniforms(const gl::Program& program, const Light& light, const LightSampleSet& samples);
// The light-sample storage buffer of shaders/common_light.glsl (PENUMBRA_SSBO_LIGHT_SAMPLES):
// N, the samples a set, in a 16-byte header, then the positions (set after set).
gl::Buffer lightSampleBuffer(const std::vector<glm::vec3>& positions, int samplesPerSet);

// Runs a full-screen fragment program (fullscreen.vert + a resolve shader) into
// pass.visibility, with the G-buffer bound and the light uniforms set.
void resolveVisibility(LightPass& pass, const gl::Program& program);
}  // namespace penumbra
