#include "techniques/evsm/evsm.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "core/error.h"
#include "core/log.h"
#include "pipeline/renderer.h"
#include "techniques/common/shadow_map/single_view.h"
#include "techniques/common/shadow_map/shaders/single_view_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra {
namespace {

class ExponentialVarianceShadowMaps final : public shadow_map::SingleViewTechnique {
 public:
  ExponentialVarianceShadowMaps(const shadow_map::SingleViewOptions& m, const EvsmOptions& o)
      : SingleViewTechnique("evsm", m), o_(o) {}

 protected:
  void renderShadow(LightPass& pass) override {
    range_ = momentDepthRange(pass);
    const double texels = double(frame().size) * double(frame().size);
    limit_ = evsmExponentLimit(o_.satBits, texels);
    positive_ = std::min(o_.positive, limit_);
    negative_ = std::min(o_.negative, limit_);
    if ((positive_ < o_.positive || negative_ < o_.negative) && !warned_) {
      PLOG_WARN(
          "evsm: exponents {} / {} exceed what the {}-bit summed-area table of {}^2 texels holds (its sums reach "
          "N exp(2 c), the warp is the float exp(c / 2) squared): clamped to the limit {:.1f}",
          o_.positive, o_.negative, o_.satBits, frame().size, limit_);
      warned_ = true;
    }
    std::vector<std::string> defines = {"MOMENTS4", "EVSM"};
    if (o_.satBits == 64) defines.push_back("DOUBLE");
    pass.timer.time(name() + " sat", [&] {
      buildMomentTable(sat_, o_.satBits == 64 ? 32 : 16, defines, range_, [&](const gl::Program& p) {
        p.set("evsmPositive", float(positive_));
        p.set("evsmNegative", float(negative_));
      });
    });
    pass.timer.time(name() + " shadow pass", [&] {
      std::vector<std::string> resolve = {"SOFT"};
      if (o_.satBits == 64) resolve.push_back("DOUBLE");
      resolveMoments(pass, program({"fullscreen.vert", "evsm_resolve.frag"}, resolve), sat_, range_,
                     [&](const gl::Program& p) {
                       p.set("evsmPositive", float(positive_));
                       p.set("evsmNegative", float(negative_));
                       p.set("subKernels", o_.subKernels);
                     });
    });
  }

  std::size_t extraBytes() const override { return sat_.size(); }

  void addStatistics(std::vector<std::pair<std::string, double>>& out) const override {
    momentStatistics(out, o_.satBits, sat_, range_);
    out.emplace_back("positive exponent", positive_);
    out.emplace_back("negative exponent", negative_);
    out.emplace_back("exponent limit", limit_);
    out.emplace_back("sub-kernels", double(o_.subKernels * o_.subKernels));
  }

 private:
  EvsmOptions o_;
  gl::Buffer sat_;
  DepthRange range_;
  double limit_ = 0.0, positive_ = 0.0, negative_ = 0.0;
  bool warned_ = false;
};

}  // namespace

double evsmExponentLimit(int satBits, double texels) {
  // The warp is exp(c u / 2) in float, squared: c <= 2 ln(FLT_MAX) for it; the table's squares'
  // sums N exp(2 c) below the format's largest value. 1% margin for the rounding of the sums.
  const double lnMax = satBits == 64 ? std::log(DBL_MAX) : std::log(double(FLT_MAX));
  const double sums = 0.99 * (lnMax - std::log(std::max(texels, 1.0))) / 2.0;
  return std::min(sums, 0.99 * 2.0 * std::log(double(FLT_MAX)));
}

std::vector<ParamSpec> evsmParams(const EvsmOptions& o) {
  std::vector<ParamSpec> p = shadow_map::singleViewParams();
  p.push_back(ParamSpec::number("positive-exponent", o.positive, 0.1, 1000.0,
                                "c+ of the positive warp exp(c+ u) (clamped to the table's limit, with a warning)"));
  p.push_back(ParamSpec::number("negative-exponent", o.negative, 0.1, 1000.0,
                                "c- of the negative warp -exp(-c- u) (clamped likewise)"));
  p.push_back(shadow_map::subKernelsParam(o.subKernels));
  p.push_back(shadow_map::satBitsParam().withDefault(o.satBits));
  return p;
}

std::unique_ptr<Technique> makeExponentialVarianceShadowMaps(const TechniqueArgs& args, EvsmOptions o) {
  o.positive = args.number("positive-exponent");
  o.negative = args.number("negative-exponent");
  o.subKernels = args.integer("sub-kernels");
  o.satBits = shadow_map::readSatBits(args);
  return std::make_unique<ExponentialVarianceShadowMaps>(shadow_map::readSingleView(args), o);
}

}  // namespace penumbra
