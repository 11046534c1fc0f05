// What the multi-view shadow-map techniques share (mvr, vwss, reproject): the light-sample
// views, the map array, and the lighting stage (per-sample shadow mapping with PCF). Each
// technique only says how its maps are made (MultiViewTechnique::renderMaps).
//
// Views: one per light sample of every sample set (layer set * N + k, the index of the sample
// in LightSampleSet::positions), all looking along one axis (the light normal of rect and disk
// lights; for sphere and point lights the direction from the light to the receivers' centroid)
// with one symmetric square frustum wide enough that every visible surface point the G-buffer
// holds is inside every sample's frustum (then so is every occluder between it and a sample),
// fitted on the GPU (FrameFit) so that no technique reads the G-buffer back.
// Reversed depth z = near / d (src/techniques/common/shadow_map/shaders/shadow_map_common.glsl).
#pragma once

#include <cstddef>
#include <functional>
#include <array>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "gl/program_cache.h"
#include "pipeline/technique.h"

namespace penumbra::shadow_map {

// The view and bias options of every shadow-map technique (multi-view and single-view).
struct MapOptions {
  int size = 1024;             // map resolution (square), as the VWSS paper's 1024^2
  double biasConstant = -1.0;  // world units along the view axis; < 0: per point, 4 x the positions' float epsilon
                               // (shadow_map_common.glsl)
  double biasSlope = 1.0;      // texels of the receiver plane's depth slope (shadow_map_common.glsl)
  double maxHalfAngle = 80.0;  // degrees: receivers needing a wider frustum are left unshadowed
};
// The declarations of map, bias, slope-bias and max-angle (every shadow-map technique's).
std::vector<ParamSpec> mapParams();
MapOptions readMapOptions(const TechniqueArgs& args);
// The uniforms of shadow_map_common.glsl biasedDepth.
void setBiasUniforms(const gl::Program& program, const MapOptions& options);

struct MapFrame {
  glm::vec3 axis{0.0f, -1.0f, 0.0f}, right{1.0f, 0.0f, 0.0f}, up{0.0f, 0.0f, 1.0f};
  float tanHalf = 1.0f;  // tangent of the frustum's half-angle (both directions)
  float zNear = 1e-3f;   // near plane of every sample view
  int size = 0;          // map resolution
  int layers = 0;        // sets * N
  // Lateral and axial reach of the views around the light centre (frame coordinates): of the
  // light samples (multi-view), or of the whole light (single-view, MapReach::Light).
  float sampleLateral = 0.0f, sampleAxialMin = 0.0f, sampleAxialMax = 0.0f;
  // Surface pixels beyond maxHalfAngle or behind the light's samples (left unshadowed; behind a
  // one-sided light too, which does not light them but whose visibility buffer, eq. 2, no map
  // holds). Their mask stays on the GPU (FrameFit::outsideMask).
  std::size_t outsidePixels = 0;
};

// What the views must reach: every light sample (multi-view: a map per sample), or the light's
// whole extent (single-view: one map from the centre, whose frustum then does not depend on
// --samples or --seed; a rect's corners, a disk's or sphere's radius).
enum class MapReach { Samples, Light };

// The frustum fitted on the GPU: reductions over the G-buffer
// (src/techniques/common/shadow_map/shaders/shadow_map_fit.comp), so no shadow-map technique reads the G-buffer back.
// Only the results come back to the CPU: the receivers' centroid (isotropic lights' axis, 32 bytes) and the widest
// receiver and the count of pixels outside (8 bytes).
class FrameFit {
 public:
  // The frame of `light`'s views over the G-buffer of `gpu` (its surface pixels): the axis (rect
  // and disk lights: their normal; sphere and point lights: towards the receivers' centroid), the
  // views' reach and near plane, and the narrowest square frustum holding every receiver within
  // options.maxHalfAngle.
  MapFrame compute(const GpuScene& gpu, const Light& light, const LightSampleSet& samples, const MapOptions& options,
                   MapReach reach);
  // Per G-buffer pixel (top row first), 1 for the last frame's outsidePixels; empty when there
  // were none. Reads the mask back (harness work: compare's reports, not the technique's).
  std::vector<std::uint8_t> outsideMask() const;

 private:
  gl::Program program_;
  gl::Buffer result_;
  gl::Texture mask_;
  std::size_t outside_ = 0;
};

// The uniforms of src/techniques/common/shadow_map/shaders/shadow_map_common.glsl.
void setMapUniforms(const gl::Program& program, const MapFrame& frame);
// One z-buffered depth map seen from `eye` (the light centre) along the frame's axis, into `fbo`
// (a DEPTH32F attachment of the frame's or another size): reproject's central map (opaque
// occluders), pcss's shadow map (semiOpaque: semi-opaque ones too, as opaque).
// `program`: mvr_depth.vert with CENTRAL, depth_only.frag.
// A pass that draws nothing while an occluder covers its view is an error naming `technique`
// (drawWithOccluderCheck).
void renderDepthView(const std::string& technique, LightPass& pass, const MapFrame& frame, const glm::vec3& eye,
                     const gl::Framebuffer& fbo, const gl::Program& program, bool semiOpaque = false);

// Self-checks (never silent). opaqueTriangleCoversAPixel: an opaque
// triangle (front-facing towards `eye` only, when cullBack) lies wholly in the view from `eye`
// along the frame's axis (near plane `zNear`, size^2 pixels) with an inscribed circle of at
// least one pixel in radius, so the rasteriser must give it a fragment (a disc of diameter
// sqrt 2 pixels holds a pixel centre). One pass over the triangles; run only when a pass came
// out empty.
bool opaqueTriangleCoversAPixel(const Scene& scene, const MapFrame& frame, const glm::vec3& eye, float zNear, int size,
                                bool cullBack);
// Runs `draw`, the depth pass `what` of `technique` for the view from `eye` (the frame's near
// plane, size^2 pixels), inside an any-samples-passed query: no fragment at all while
// opaqueTriangleCoversAPixel is an error (the GL ran no fragment or lost them), not an
// unshadowed image.
void drawWithOccluderCheck(const std::string& technique, const std::string& what, const Scene& scene,
                           const MapFrame& frame, const glm::vec3& eye, int size, const std::function<void()>& draw);

// Distance beyond the samples (along the axis) of the nearest scene vertex in front of them:
// where the samples' near plane could sit without clipping an occluder (VWSS eq. 3's z_n, the
// pcss blocker-search plane). Cached per light and axis (one pass over the vertices).
// `surfaces`: the nearest point of any triangle instead, the near plane itself for a triangle
// that reaches from behind the samples to in front of them (a light inside a tube or a box,
// hard case 29: the walls pass the light closer than any vertex), as a bound on every
// occluder's depth (vssm's depth range).
class NearestOccluder {
 public:
  float get(const Scene& scene, int lightIndex, const glm::vec3& centre, const MapFrame& frame, bool surfaces = false);

 private:
  std::map<std::tuple<int, std::array<float, 3>, bool>, float> cache_;
};

// Triangles of meshes whose material is semi-opaque (opacity in (0, 1)).
std::size_t semiOpaqueTriangles(const Scene& scene);

// A technique whose visibility is shadow mapping in one map per light sample.
// Semi-opaque occluders (only when the scene has some): left out of the technique's opaque maps
// and rasterised per map (one layered draw, as mvr-layered) into a per-texel list of K entries
// (depth and opacity of each semi-opaque surface on the texel's ray), K sized to the scene: the
// most surfaces any texel holds, measured in the same pass (a frame that needs more is redone
// with enough, statistic "semi-opaque reruns"). The lighting multiplies a sample's visibility by
// 1 - opacity of every entry nearer to the sample than the receiver, as the reference does along
// its ray. Points cannot carry this (several points of one surface land on a texel), so vwss and
// reproject use the same rasterised lists.
class MultiViewTechnique : public Technique {
 public:
  // pcf: taps per map, 1, 5 (the VWSS paper's) or 9 (readPcfTaps).
  MultiViewTechnique(std::string name, const MapOptions& options, int pcf)
      : name_(std::move(name)), options_(options), pcf_(pcf) {}
  void prepare(const Scene& scene, GpuScene& gpu) override;
  void renderVisibility(LightPass& pass) override;
  bool providesPerSample() const override { return true; }
  std::size_t memoryBytes() const override {
    return maps_.bytes() + semiCount_.bytes() + semiLayers_.bytes() + extraBytes();
  }
  std::vector<std::pair<std::string, double>> statistics() const override;
  std::vector<std::uint8_t> unshadowedPixels() const override { return fit_.outsideMask(); }

 protected:
  // Fill the maps for `frame`: ensureMaps() then render into them.
  virtual void renderMaps(LightPass& pass, const MapFrame& frame) = 0;
  virtual std::size_t extraBytes() const { return 0; }
  virtual void addStatistics(std::vector<std::pair<std::string, double>>& out) const {}
  // The map array for `frame`: DEPTH32F (rasterised) or R32UI (point-splatted), cleared to
  // "nothing" (depth 0 = infinitely far). Throws penumbra::Error if the GL cannot hold it.
  const gl::Texture& ensureMaps(GLenum format, const MapFrame& frame);
  const std::string& name() const { return name_; }
  const MapOptions& options() const { return options_; }
  const gl::Texture& maps() const { return maps_; }
  // The technique's programs by shaders and defines.
  gl::ProgramCache& programs() { return programs_; }

 private:
  const gl::Program& resolveProgram(bool perSample);
  void renderSemiOpaque(LightPass& pass, const MapFrame& frame);
  std::string name_;
  MapOptions options_;
  int pcf_;
  gl::Texture maps_;
  gl::ProgramCache programs_;
  MapFrame frame_;
  FrameFit fit_;
  std::size_t semiOpaque_ = 0;
  gl::Texture semiCount_, semiLayers_;
  gl::Framebuffer semiFbo_;
  gl::Texture
      semiStatus_;  // 1 x 1 R32UI image (src/techniques/common/shadow_map/shaders/shadow_map_transmittance.frag)
  int semiSlots_ = 0, semiReruns_ = 0;
};

// Reads pcf (taps per map: 1, 5 or 9; default 5) from --param.
// pcf, the multi-view techniques' taps per map (1, 5 or 9).
ParamSpec pcfParam();
int readPcfTaps(const TechniqueArgs& args);

// Dispatches the bound compute program over `threads` invocations of PENUMBRA_MAP_LOCAL_SIZE-wide
// groups, split over y beyond 65535 groups (src/techniques/common/shadow_map/shaders/compute_index.glsl globalIndex).
void dispatchThreads(std::size_t threads);

// Point rendering into an R32UI map array with compute
// (src/techniques/common/shadow_map/shaders/shadow_map_reproject.comp): `mapsPerThread` maps per traversal of the
// points (1: serial, 0 or >= layers: fully parallel).
struct SplatOptions {
  int mapsPerThread = 8;
  bool synchronized = true;  // imageAtomicMax; false: plain stores (last writer wins)
};
// Binds `maps` as the splat image and dispatches over `threads` points, once per group of maps.
// `program` has the uniforms of shadow_map_common.glsl set. Returns the number of dispatches.
int splatMaps(const gl::Program& program, const gl::Texture& maps, std::size_t threads, int layers,
              const SplatOptions& options);

}  // namespace penumbra::shadow_map
