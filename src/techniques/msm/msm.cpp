#include "techniques/msm/msm.h"

#include "core/error.h"
#include "pipeline/renderer.h"
#include "techniques/common/shadow_map/single_view.h"
#include "techniques/common/shadow_map/shaders/single_view_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra {
namespace {

class MomentShadowMapping final : public shadow_map::SingleViewTechnique {
 public:
  MomentShadowMapping(const shadow_map::SingleViewOptions& m, const MsmOptions& o)
      : SingleViewTechnique(o.soft ? "msm-soft" : "msm", m), o_(o) {}

 protected:
  void renderShadow(LightPass& pass) override {
    range_ = momentDepthRange(pass);
    std::vector<std::string> defines = {"MOMENTS4"};
    if (o_.satBits == 64) defines.push_back("DOUBLE");
    if (o_.translucent) {
      pass.timer.time(name() + " translucent moments", [&] { renderTranslucentMoments(pass); });
      defines.push_back("MOMENT_MAP");
      moments_.bind(PENUMBRA_UNIT_PCSS_AUX);
    }
    pass.timer.time(name() + " sat", [&] { buildMomentTable(sat_, o_.satBits == 64 ? 32 : 16, defines, range_); });
    pass.timer.time(name() + " shadow pass", [&] {
      std::vector<std::string> resolve;
      if (o_.satBits == 64) resolve.push_back("DOUBLE");
      if (o_.soft) resolve.push_back("SOFT");
      resolveMoments(pass, program({"fullscreen.vert", "msm_resolve.frag"}, resolve), sat_, range_,
                     [&](const gl::Program& p) {
                       p.set("momentBias", float(o_.momentBias));
                       p.set("filterTexels", o_.filter);
                       p.set("subKernels", o_.subKernels);
                     });
    });
  }

  std::size_t extraBytes() const override { return sat_.size() + moments_.bytes() + momentDepth_.bytes(); }

  void addStatistics(std::vector<std::pair<std::string, double>>& out) const override {
    momentStatistics(out, o_.satBits, sat_, range_);
    out.emplace_back("moment bias", o_.momentBias);
    if (!o_.soft) out.emplace_back("filter texels", double(o_.filter));
    if (o_.soft) out.emplace_back("sub-kernels", double(o_.subKernels * o_.subKernels));
    out.emplace_back("translucent", o_.translucent ? 1.0 : 0.0);
  }

 private:
  // The moment map of msm_translucent.frag: the opaque occluders' moments with depth writes, then
  // the semi-opaque ones blended over them by their opacity, in the scene's draw order.
  void renderTranslucentMoments(LightPass& pass) {
    const int size = frame().size;
    if (moments_.width() != size) {
      momentFbo_ = gl::Framebuffer();
      moments_ = gl::Texture::make2D(GL_RGBA32F, size, size);
      momentDepth_ = gl::Texture::make2D(GL_DEPTH_COMPONENT32F, size, size);
      momentFbo_ = gl::Framebuffer({&moments_}, &momentDepth_);
    }
    momentFbo_.bind();
    const float far[4] = {1.0f, 1.0f, 1.0f, 1.0f}, zero = 0.0f;  // u = 1: nothing (reversed depth 0)
    glClearNamedFramebufferfv(momentFbo_.id(), GL_COLOR, 0, far);
    glClearNamedFramebufferfv(momentFbo_.id(), GL_DEPTH, 0, &zero);
    const gl::Program& p = program({"mvr_depth.vert", "msm_translucent.frag"}, {"CENTRAL"});
    p.use();
    shadow_map::setMapUniforms(p, frame());
    p.set("eye", pass.light.position);
    p.set("mapNear", frame().zNear);
    p.set("depthMin", range_.min);
    p.set("depthMax", range_.max);
    p.set("opacity", 1.0f);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    pass.gpu.drawTriangles(1, GpuScene::Occluders::Opaque, p);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_SRC1_ALPHA, GL_ONE_MINUS_SRC1_ALPHA);
    pass.gpu.drawTriangles(1, GpuScene::Occluders::SemiOpaque, p);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }

  MsmOptions o_;
  gl::Buffer sat_;
  DepthRange range_;
  gl::Texture moments_, momentDepth_;  // translucent: the blended moment map
  gl::Framebuffer momentFbo_;
};

}  // namespace

std::vector<ParamSpec> msmParams(const MsmOptions& o) {
  std::vector<ParamSpec> p = shadow_map::singleViewParams();
  if (!o.soft)
    p.push_back(ParamSpec::integer("filter", o.filter, 1, 63,
                                   "width in texels of the box the moments are filtered over (odd)"));
  if (o.soft) p.push_back(shadow_map::subKernelsParam(o.subKernels));
  p.push_back(ParamSpec::number(
      "moment-bias", o.momentBias, 0.0, 0.1,
      "alpha: the share by which a box's standardised moments are pulled towards a uniform distribution's"));
  p.push_back(shadow_map::satBitsParam().withDefault(o.satBits));
  p.push_back(ParamSpec::boolean("translucent", o.translucent,
                                 "semi-opaque occluders blend their moments by their opacity (the MSM-SOFT paper's "
                                 "translucent occluders) instead of being drawn as opaque"));
  return p;
}

std::unique_ptr<Technique> makeMomentShadowMapping(const TechniqueArgs& args, MsmOptions o) {
  if (!o.soft) {
    o.filter = args.integer("filter");
    if (o.filter % 2 == 0)
      throw Error("param", "filter: must be odd, got " + std::to_string(o.filter), ExitCode::Usage);
  }
  if (o.soft) o.subKernels = args.integer("sub-kernels");
  o.momentBias = args.number("moment-bias");
  o.satBits = shadow_map::readSatBits(args);
  o.translucent = args.boolean("translucent");
  return std::make_unique<MomentShadowMapping>(shadow_map::readSingleView(args), o);
}

}  // namespace penumbra
