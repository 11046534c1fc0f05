// What the single-view shadow-map techniques share (pcss, vssm): one depth map from the light
// centre (the frustum and bias of maps.h; the frustum holds the whole light, MapReach::Light, so
// --samples and --seed do not change it), the raw and comparison samplers of it, the uniforms of
// src/techniques/common/shadow_map/shaders/pcss_common.glsl, and a cache of programs. Each technique adds its passes in
// renderShadow().
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gl/objects.h"
#include "gl/program_cache.h"
#include "pipeline/technique.h"
#include "techniques/common/shadow_map/contact.h"
#include "techniques/common/shadow_map/maps.h"
#include "techniques/common/shadow_map/shaders/single_view_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra::shadow_map {

// The four-moment summed-area-table techniques' shared parameters (msm, msm-soft, evsm):
// sat-bits (the table's precision, 64 or 32) and sub-kernels (each kernel split into n x n with
// their own receiver depths), declared here once; readSatBits refuses other precisions.
ParamSpec satBitsParam();
ParamSpec subKernelsParam(int fallback);
int readSatBits(const TechniqueArgs& args);

// What every single-view technique takes: the map's options (maps.h) and contact shadows
// (contact.h), declared once: singleViewParams, read by readSingleView.
struct SingleViewOptions {
  MapOptions map;
  ContactOptions contact;
};
std::vector<ParamSpec> singleViewParams(const ContactOptions& contact = {});
SingleViewOptions readSingleView(const TechniqueArgs& args);

class SingleViewTechnique : public Technique {
 public:
  SingleViewTechnique(std::string name, const SingleViewOptions& o)
      : name_(std::move(name)), map_(o.map), contact_(o.contact) {}
  void prepare(const Scene& scene, GpuScene& gpu) override;
  // Views, the map ("<name> shadow map"), then renderShadow(), then contact shadows if asked.
  void renderVisibility(LightPass& pass) override;
  std::size_t memoryBytes() const override { return depth_.bytes() + extraBytes(); }
  std::vector<std::pair<std::string, double>> statistics() const override;
  std::vector<std::uint8_t> unshadowedPixels() const override { return fit_.outsideMask(); }
  bool cullsSeparatedLights() const override { return true; }  // one map from the centre

 protected:
  virtual void renderShadow(LightPass& pass) = 0;
  virtual std::size_t extraBytes() const { return 0; }
  virtual void addStatistics(std::vector<std::pair<std::string, double>>& out) const {}

  const std::string& name() const { return name_; }
  const MapFrame& frame() const { return frame_; }
  const gl::Texture& depth() const { return depth_; }
  float searchNear() const { return searchNear_; }  // nearest occluder's view depth
  // The nearest triangle point's view depth (NearestOccluder surfaces: a bound on every occluder).
  float nearestSurface(const LightPass& pass) {
    return nearest_.get(pass.scene, pass.lightIndex, pass.light.position, frame_, true);
  }
  float lightHalfSize() const { return halfSize_; }  // the parallel-planes light size
  // The depth range of the moment techniques' normalised depth (vssm, msm, evsm: shaders/
  // vssm_common.glsl): from the nearest occluder surface to the farthest scene point ahead of the
  // light along the map's axis.
  struct DepthRange {
    float min = 0.0f, max = 1.0f;
  };
  DepthRange momentDepthRange(const LightPass& pass);
  // The summed-area table of the depth moments (src/techniques/common/shadow_map/shaders/vssm_sat.comp, its defines)
  // into `sat`, sized to `bytesPerTexel`, over `range`. `uniforms` sets the table program's own (evsm's exponents).
  void buildMomentTable(gl::Buffer& sat, std::size_t bytesPerTexel, const std::vector<std::string>& defines,
                        const DepthRange& range, const std::function<void(const gl::Program&)>& uniforms = {});
  // The shadow pass of a four-moment table technique (src/techniques/common/shadow_map/shaders/moment_soft.glsl): `p`
  // with the framework's uniforms, the depth range and its own (`uniforms`), the table and the map bound, into the
  // visibility buffer.
  void resolveMoments(LightPass& pass, const gl::Program& p, const gl::Buffer& sat, const DepthRange& range,
                      const std::function<void(const gl::Program&)>& uniforms);
  // Their statistics: the table's precision and bytes, the depth range.
  static void momentStatistics(std::vector<std::pair<std::string, double>>& out, int satBits, const gl::Buffer& sat,
                               const DepthRange& range);
  // Binds the map raw (PENUMBRA_UNIT_PCSS_DEPTH) and through the comparison sampler
  // (PENUMBRA_UNIT_PCSS_COMPARE).
  void bindMap() const;
  // The uniforms of src/techniques/common/shadow_map/shaders/pcss_common.glsl (and the light's).
  void setUniforms(const gl::Program& p, const LightPass& pass, int blockerSamples, int pcfSamples,
                   double kernelScale) const;
  // The program of `files` and `defines`, built once (gl::ProgramCache).
  const gl::Program& program(const std::vector<std::string>& files, const std::vector<std::string>& defines);
  // A full-screen triangle into `fbo` (bound) with `p`.
  void drawFullscreen(const gl::Framebuffer& fbo, const gl::Program& p) const;

 private:
  std::string name_;
  MapOptions map_;
  MapFrame frame_;
  FrameFit fit_;
  NearestOccluder nearest_;
  ContactShadows contact_;
  gl::Texture depth_;
  gl::Framebuffer depthFbo_;
  gl::Sampler raw_, compare_;
  gl::VertexArray vao_;
  gl::ProgramCache programs_;
  std::size_t semiOpaque_ = 0;
  float searchNear_ = 0.0f, halfSize_ = 0.0f;
};

}  // namespace penumbra::shadow_map
