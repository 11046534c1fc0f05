#include "techniques/mvr/mvr.h"

#include "pipeline/renderer.h"
#include "techniques/common/shadow_map/maps.h"

namespace penumbra {
namespace {

class MultiViewRasterisation final : public shadow_map::MultiViewTechnique {
 public:
  MultiViewRasterisation(const shadow_map::MapOptions& o, int pcf, bool layered)
      : MultiViewTechnique(layered ? "mvr-layered" : "mvr", o, pcf), layered_(layered) {}

 protected:
  void renderMaps(LightPass& pass, const shadow_map::MapFrame& frame) override {
    const gl::Texture& maps = ensureMaps(GL_DEPTH_COMPONENT32F, frame);
    pass.timer.time(name() + " depth maps", [&] {
      const gl::Program& program =
          layered_ ? programs().get({"mvr_depth.vert", "mvr_depth.geom", "depth_only.frag"}, {"LAYERED"})
                   : programs().get({"mvr_depth.vert", "depth_only.frag"});
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_GREATER);  // reversed depth
      glDepthMask(GL_TRUE);
      glDisable(GL_CULL_FACE);
      glDisable(GL_BLEND);
      program.use();
      shadow_map::setMapUniforms(program, frame);
      // No fragment in any map is checked against the first sample's view (map 0).
      shadow_map::drawWithOccluderCheck(
          name(), "depth maps", pass.scene, frame, pass.samples.positions.at(0), frame.size, [&] {
            if (layered_) {
              if (!layeredFbo_ || fboFor_ != maps.id())
                layeredFbo_ = gl::Framebuffer(std::vector<gl::Framebuffer::Attachment>{}, &maps);
              layeredFbo_.bind();
              pass.gpu.drawTriangles(frame.layers, GpuScene::Occluders::Opaque, program);
            } else {
              if (fboFor_ != maps.id()) {
                layerFbos_.clear();
                for (int l = 0; l < frame.layers; ++l)
                  layerFbos_.emplace_back(std::vector<gl::Framebuffer::Attachment>{}, &maps, l);
              }
              for (int l = 0; l < frame.layers; ++l) {
                layerFbos_[std::size_t(l)].bind();
                program.set("layer", l);
                pass.gpu.drawTriangles(1, GpuScene::Occluders::Opaque, program);
              }
            }
          });
      fboFor_ = maps.id();
      glDisable(GL_DEPTH_TEST);
    });
  }
  void addStatistics(std::vector<std::pair<std::string, double>>& out) const override {
    out.emplace_back("draws", layered_ ? 1.0 : double(layerFbos_.size()));
  }

 private:
  bool layered_;
  gl::Framebuffer layeredFbo_;
  std::vector<gl::Framebuffer> layerFbos_;
  GLuint fboFor_ = 0;
};

}  // namespace

std::vector<ParamSpec> mvrParams() {
  std::vector<ParamSpec> p = shadow_map::mapParams();
  p.push_back(shadow_map::pcfParam());
  return p;
}

std::unique_ptr<Technique> makeMultiViewRasterisation(const TechniqueArgs& args, bool layered) {
  return std::make_unique<MultiViewRasterisation>(shadow_map::readMapOptions(args), shadow_map::readPcfTaps(args),
                                                  layered);
}

}  // namespace penumbra
