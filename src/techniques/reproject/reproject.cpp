#include "techniques/reproject/reproject.h"

#include <cmath>

#include "pipeline/renderer.h"
#include "sampling/shared.hpp"
#include "techniques/shadow_map/maps.h"

namespace penumbra {
namespace {

class FragmentReprojection final : public shadow_map::MultiViewTechnique {
 public:
  FragmentReprojection(const shadow_map::MapOptions& m, int pcf, double scale, const shadow_map::SplatOptions& s)
      : MultiViewTechnique(s.synchronized ? "reproject" : "reproject-unsync", m, pcf), scale_(scale), splat_(s) {}

 protected:
  void renderMaps(LightPass& pass, const shadow_map::MapFrame& frame) override {
    const gl::Texture& maps = ensureMaps(GL_R32UI, frame);
    const int size = std::max(1, int(std::lround(double(frame.size) * scale_)));
    pass.timer.time(name() + " central map", [&] {
      if (central_.width() != size) {
        central_ = gl::Texture::make2D(GL_DEPTH_COMPONENT32F, size, size);
        centralFbo_ = gl::Framebuffer(std::vector<gl::Framebuffer::Attachment>{}, &central_);
      }
      if (!depthProgram_) depthProgram_ = gl::Program({"mvr_depth.vert", "depth_only.frag"}, {"CENTRAL"});
      shadow_map::renderDepthView(name(), pass, frame, pass.light.position, centralFbo_, depthProgram_);
    });
    pass.timer.time(name() + " depth maps", [&] {
      if (!splatProgram_) {
        std::vector<std::string> defs = {"FROM_DEPTH_MAP"};
        if (!splat_.synchronized) defs.push_back("UNSYNCHRONIZED");
        splatProgram_ = gl::Program({"shadow_map_reproject.comp"}, defs);
      }
      shadow_map::setMapUniforms(splatProgram_, frame);
      splatProgram_.set("centralEye", pass.light.position);
      splatProgram_.set("centralSize", size);
      central_.bind(PENUMBRA_UNIT_CENTRAL_DEPTH);
      dispatches_ = shadow_map::splatMaps(splatProgram_, maps, std::size_t(size) * std::size_t(size), frame.layers, splat_);
    });
  }
  std::size_t extraBytes() const override { return central_.bytes(); }
  void addStatistics(std::vector<std::pair<std::string, double>>& out) const override {
    out.emplace_back("central map size", central_.width());
    out.emplace_back("maps per thread", splat_.mapsPerThread);
    out.emplace_back("point passes", dispatches_);
  }

 private:
  double scale_;
  shadow_map::SplatOptions splat_;
  gl::Texture central_;
  gl::Framebuffer centralFbo_;
  gl::Program depthProgram_, splatProgram_;
  int dispatches_ = 0;
};

}  // namespace

std::unique_ptr<Technique> makeFragmentReprojection(const TechniqueParams& params, bool synchronized) {
  shadow_map::SplatOptions s;
  s.synchronized = synchronized;
  s.mapsPerThread = params.getInt("k", 0, 0, 4096);
  double scale = params.getDouble("scale", 1.0, 0.125, 16.0);
  return std::make_unique<FragmentReprojection>(shadow_map::readMapOptions(params), shadow_map::readPcfTaps(params), scale, s);
}

}  // namespace penumbra
