#include "techniques/reproject/reproject.h"

#include <cmath>

#include "pipeline/renderer.h"
#include "shared/shared.h"  // NOLINT: shared with GLSL
#include "techniques/common/shadow_map/maps.h"
#include "techniques/common/shadow_map/shaders/shadow_map_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra {
namespace {

class FragmentReprojection final : public shadow_map::MultiViewTechnique {
 public:
  FragmentReprojection(const shadow_map::MapOptions& m, int pcf, double scale, const shadow_map::SplatOptions& s)
      : MultiViewTechnique(s.synchronized ? "reproject" : "reproject-unsync", m, pcf), scale_(scale), splat_(s) {}
  bool cullsSeparatedLights() const override { return true; }  // every map reprojected from the centre's

 protected:
  void renderMaps(LightPass& pass, const shadow_map::MapFrame& frame) override {
    const gl::Texture& maps = ensureMaps(GL_R32UI, frame);
    const int size = std::max(1, int(std::lround(double(frame.size) * scale_)));
    pass.timer.time(name() + " central map", [&] {
      if (central_.width() != size) {
        central_ = gl::Texture::make2D(GL_DEPTH_COMPONENT32F, size, size);
        centralFbo_ = gl::Framebuffer(std::vector<gl::Framebuffer::Attachment>{}, &central_);
      }
      shadow_map::renderDepthView(name(), pass, frame, pass.light.position, centralFbo_,
                                  programs().get({"mvr_depth.vert", "depth_only.frag"}, {"CENTRAL"}));
    });
    pass.timer.time(name() + " depth maps", [&] {
      std::vector<std::string> defs = {"FROM_DEPTH_MAP"};
      if (!splat_.synchronized) defs.push_back("UNSYNCHRONIZED");
      const gl::Program& splat = programs().get({"shadow_map_reproject.comp"}, defs);
      shadow_map::setMapUniforms(splat, frame);
      splat.set("centralEye", pass.light.position);
      splat.set("centralSize", size);
      central_.bind(PENUMBRA_UNIT_CENTRAL_DEPTH);
      dispatches_ = shadow_map::splatMaps(splat, maps, std::size_t(size) * std::size_t(size), frame.layers, splat_);
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
  int dispatches_ = 0;
};

}  // namespace

std::vector<ParamSpec> reprojectParams() {
  std::vector<ParamSpec> p = shadow_map::mapParams();
  p.push_back(shadow_map::pcfParam());
  p.push_back(ParamSpec::integer("k", 0, 0, 4096, "maps per compute thread: 1 serial, 0 all (fully parallel)"));
  p.push_back(
      ParamSpec::number("scale", 1.0, 0.125, 16.0,
                        "central-map resolution over the map resolution (the paper raises it to fill gaps, 4.2.1)"));
  return p;
}

std::unique_ptr<Technique> makeFragmentReprojection(const TechniqueArgs& args, bool synchronized) {
  shadow_map::SplatOptions s;
  s.synchronized = synchronized;
  s.mapsPerThread = args.integer("k");
  double scale = args.number("scale");
  return std::make_unique<FragmentReprojection>(shadow_map::readMapOptions(args), shadow_map::readPcfTaps(args), scale,
                                                s);
}

}  // namespace penumbra
