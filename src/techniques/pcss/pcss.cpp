#include "techniques/pcss/pcss.h"

#include <cmath>

#include "gl/context.h"
#include "pipeline/renderer.h"
#include "sampling/shared.hpp"
#include "techniques/shadow_map/maps.h"

namespace penumbra {
namespace {

// Half the side of the square of the light's area (rect, disk) or of the disc a sphere shows:
// the light "size" of the parallel-planes estimate.
float lightHalfSize(const Light& light) {
  switch (light.shape) {
    case LightShape::Rect:
    case LightShape::Disk: return 0.5f * std::sqrt(light.area());
    case LightShape::Sphere: return 0.5f * std::sqrt(float(M_PI)) * light.size.x;
    default: return 0.0f;
  }
}

class PercentageCloserSoftShadows final : public Technique {
 public:
  PercentageCloserSoftShadows(const shadow_map::MapOptions& m, PcssPreset p) : map_(m), preset_(p) {}

  void prepare(const Scene& scene, GpuScene&) override {
    semiOpaque_ = shadow_map::semiOpaqueTriangles(scene);
    nearest_ = {};
  }

  void renderVisibility(LightPass& pass) override {
    frame_ = pass.timer.time("pcss views", [&] {
      return shadow_map::computeMapFrame(pass.scene, pass.light, pass.samples, pass.cpuGBuffer(), map_);
    });
    searchNear_ = nearest_.get(pass.scene, pass.lightIndex, pass.light.position, frame_);
    halfSize_ = lightHalfSize(pass.light);
    pass.timer.time("pcss shadow map", [&] {
      if (depth_.width() != frame_.size) {
        fbo_ = gl::Framebuffer();
        depth_ = gl::Texture::make2D(GL_DEPTH_COMPONENT32F, frame_.size, frame_.size);
        fbo_ = gl::Framebuffer(std::vector<gl::Framebuffer::Attachment>{}, &depth_);
      }
      if (!depthProgram_) depthProgram_ = gl::Program({"mvr_depth.vert", "depth_only.frag"}, {"CENTRAL"});
      shadow_map::renderDepthView(pass, frame_, pass.light.position, fbo_, depthProgram_, true);
    });
    pass.timer.time("pcss lighting", [&] {
      if (!program_) {
        program_ = gl::Program({"fullscreen.vert", "pcss_resolve.frag"});
        raw_ = gl::Sampler::make(false, 0.0f);
        compare_ = gl::Sampler::make(true, 0.0f, GL_GEQUAL);  // lit where the receiver is nearer or level
      }
      shadow_map::setMapUniforms(program_, frame_);
      shadow_map::setBiasUniforms(program_, map_, pass.scene);
      program_.set("eyePosition", pass.gpu.cameraPosition());
      program_.set("surfaceOffset", pass.scene.surfaceOffset());
      program_.set("lightHalfSize", halfSize_);
      program_.set("searchNear", searchNear_);
      program_.set("blockerSamples", preset_.blockerSamples);
      program_.set("pcfSamples", preset_.pcfSamples);
      depth_.bind(PENUMBRA_UNIT_PCSS_DEPTH);
      depth_.bind(PENUMBRA_UNIT_PCSS_COMPARE);
      raw_.bind(PENUMBRA_UNIT_PCSS_DEPTH);
      compare_.bind(PENUMBRA_UNIT_PCSS_COMPARE);
      resolveVisibility(pass, program_);
      gl::Sampler::unbind(PENUMBRA_UNIT_PCSS_DEPTH);
      gl::Sampler::unbind(PENUMBRA_UNIT_PCSS_COMPARE);
    });
    gl::Context::checkErrors("pcss");
  }

  std::size_t memoryBytes() const override { return depth_.bytes(); }

  std::vector<std::pair<std::string, double>> statistics() const override {
    return {{"map size", frame_.size},
            {"blocker samples", preset_.blockerSamples},
            {"pcf samples", preset_.pcfSamples},
            {"frustum half-angle deg", glm::degrees(std::atan(frame_.tanHalf))},
            {"pixels outside maps", double(frame_.outsidePixels)},
            {"search near", searchNear_},
            {"light half size", halfSize_},
            {"map bytes", double(depth_.bytes())},
            {"semi-opaque triangles as opaque", double(semiOpaque_)}};
  }

 private:
  shadow_map::MapOptions map_;
  PcssPreset preset_;
  shadow_map::MapFrame frame_;
  shadow_map::NearestOccluder nearest_;
  gl::Texture depth_;
  gl::Framebuffer fbo_;
  gl::Program depthProgram_, program_;
  gl::Sampler raw_, compare_;
  std::size_t semiOpaque_ = 0;
  float searchNear_ = 0.0f, halfSize_ = 0.0f;
};

}  // namespace

std::unique_ptr<Technique> makePercentageCloserSoftShadows(const TechniqueParams& params, PcssPreset preset) {
  preset.blockerSamples = params.getInt("blocker-samples", preset.blockerSamples, 1, 256);
  preset.pcfSamples = params.getInt("pcf-samples", preset.pcfSamples, 1, 256);
  return std::make_unique<PercentageCloserSoftShadows>(shadow_map::readMapOptions(params), preset);
}

}  // namespace penumbra
