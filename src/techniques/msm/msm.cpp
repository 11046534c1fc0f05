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

  std::size_t extraBytes() const override { return sat_.size(); }

  void addStatistics(std::vector<std::pair<std::string, double>>& out) const override {
    momentStatistics(out, o_.satBits, sat_, range_);
    out.emplace_back("moment bias", o_.momentBias);
    if (!o_.soft) out.emplace_back("filter texels", double(o_.filter));
    if (o_.soft) out.emplace_back("sub-kernels", double(o_.subKernels * o_.subKernels));
  }

 private:
  MsmOptions o_;
  gl::Buffer sat_;
  DepthRange range_;
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
  return std::make_unique<MomentShadowMapping>(shadow_map::readSingleView(args), o);
}

}  // namespace penumbra
