#include "techniques/vssm/vssm.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "pipeline/renderer.h"
#include "shared/shared.h"  // NOLINT: shared with GLSL
#include "techniques/common/shadow_map/single_view.h"
#include "techniques/common/shadow_map/shaders/single_view_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra {
namespace {

class VarianceSoftShadowMapping final : public shadow_map::SingleViewTechnique {
 public:
  VarianceSoftShadowMapping(const shadow_map::SingleViewOptions& m, const VssmOptions& o)
      : SingleViewTechnique(!o.exactSat          ? "vssm-fp32"
                            : o.shadowLevels > 0 ? "vssm"
                                                 : "vssm-uniform",
                            m),
        o_(o) {}

 protected:
  void renderShadow(LightPass& pass) override {
    const auto& f = frame();
    const DepthRange range = momentDepthRange(pass);
    depthMin_ = range.min;
    depthMax_ = range.max;
    glm::vec3 lo, hi;
    pass.scene.bounds(lo, hi);
    // Threshold = 1e-4 r (section 6.5), as a variance of the normalised depth; the contact
    // fallback's epsilon = 0.01 r (section 5.3). The paper's r is the scene's bounding radius;
    // ours is at most the radius of the part of the scene the map sees (its frustum between
    // depthMin and depthMax), so that geometry far outside the map (a 1e5-unit floor, hard case
    // 25) does not turn every blocker into a contact.
    const float lateral = f.tanHalf * depthMax_;
    const float viewRadius =
        0.5f * std::sqrt(8.0f * lateral * lateral + (depthMax_ - depthMin_) * (depthMax_ - depthMin_));
    const float radius = std::min(0.5f * glm::length(hi - lo), viewRadius);
    threshold_ = float(std::pow(1e-4 * radius / (depthMax_ - depthMin_), 2.0));
    contactEpsilon_ = 0.01f * radius;
    if (f.size & (f.size - 1))
      throw Error(name(),
                  "map size " + std::to_string(f.size) + " is not a power of two (the min-max hierarchy halves it)",
                  ExitCode::Usage);

    pass.timer.time(name() + " sat", [&] {
      buildMomentTable(sat_, o_.exactSat ? 16 : 8,
                       o_.exactSat ? std::vector<std::string>{"EXACT"} : std::vector<std::string>{}, range);
    });
    pass.timer.time(name() + " hsm", [&] {
      hsmLevels_ = 0;
      std::size_t texels = 0;
      for (int s = f.size; s >= 1; s /= 2) texels += std::size_t(s) * std::size_t(s), ++hsmLevels_;
      if (hsm_.size() != texels * 8) hsm_ = gl::Buffer(texels * 8, nullptr);
      hsm_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_VSSM_HSM);
      const gl::Program& p = program({"vssm_hsm.comp"}, {});
      p.set("satSize", f.size);
      p.set("mapNear", f.zNear);
      p.set("depthMin", depthMin_);
      p.set("depthMax", depthMax_);
      p.use();
      for (int level = 0; level < hsmLevels_; ++level) {
        p.set("level", level);
        shadow_map::dispatchThreads(std::size_t(f.size >> level) * std::size_t(f.size >> level));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
      }
    });
    pass.timer.time(name() + " shadow pass", [&] {
      const gl::Program& p = program({"fullscreen.vert", "vssm_resolve.frag"},
                                     o_.exactSat ? std::vector<std::string>{"EXACT"} : std::vector<std::string>{});
      setUniforms(p, pass, 0, 0, 1.0);
      p.set("depthMin", depthMin_);
      p.set("depthMax", depthMax_);
      p.set("blockerDiv", o_.blockerDiv);
      p.set("shadowDiv", o_.shadowDiv);
      p.set("threshold", threshold_);
      p.set("blockerLevels", o_.blockerLevels);
      p.set("shadowLevels", o_.shadowLevels);
      p.set("contactEpsilon", contactEpsilon_);
      p.set("hsmLevels", hsmLevels_);
      sat_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_VSSM_SAT);
      hsm_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_VSSM_HSM);
      bindMap();
      resolveVisibility(pass, p);
    });
  }

  std::size_t extraBytes() const override { return sat_.size() + hsm_.size(); }

  void addStatistics(std::vector<std::pair<std::string, double>>& out) const override {
    out.emplace_back("exact sat", o_.exactSat ? 1.0 : 0.0);
    out.emplace_back("blocker sub-kernels", o_.blockerLevels > 0 ? double(1 << (2 * o_.blockerLevels))
                                                                 : double(o_.blockerDiv * o_.blockerDiv));
    out.emplace_back("shadow sub-kernels",
                     o_.shadowLevels > 0 ? double(1 << (2 * o_.shadowLevels)) : double(o_.shadowDiv * o_.shadowDiv));
    out.emplace_back("adaptive shadow levels", double(o_.shadowLevels));
    out.emplace_back("hsm levels", double(hsmLevels_));
    out.emplace_back("hsm bytes", double(hsm_.size()));
    out.emplace_back("depth min", depthMin_);
    out.emplace_back("depth max", depthMax_);
    out.emplace_back("sat bytes", double(sat_.size()));
  }

 private:
  VssmOptions o_;
  gl::Buffer sat_, hsm_;
  int hsmLevels_ = 0;
  float depthMin_ = 0.0f, depthMax_ = 1.0f, threshold_ = 0.0f, contactEpsilon_ = 0.0f;
};

}  // namespace

std::vector<ParamSpec> vssmParams(const VssmOptions& o) {
  std::vector<ParamSpec> p = shadow_map::singleViewParams();
  p.push_back(
      ParamSpec::integer("blocker-div", o.blockerDiv, 1, 16, "uniform m x m sub-kernels of the blocker search"));
  p.push_back(ParamSpec::integer("shadow-div", o.shadowDiv, 1, 16, "uniform n x n sub-kernels of the visibility"));
  p.push_back(ParamSpec::integer("blocker-levels", o.blockerLevels, 0, 5,
                                 "adaptive quad-tree height of the blocker search (0: uniform)"));
  p.push_back(ParamSpec::integer("shadow-levels", o.shadowLevels, 0, 5,
                                 "adaptive quad-tree height H of the visibility (0: uniform)"));
  return p;
}

std::unique_ptr<Technique> makeVarianceSoftShadowMapping(const TechniqueArgs& args, VssmOptions o) {
  o.blockerDiv = args.integer("blocker-div");
  o.shadowDiv = args.integer("shadow-div");
  o.blockerLevels = args.integer("blocker-levels");
  o.shadowLevels = args.integer("shadow-levels");
  return std::make_unique<VarianceSoftShadowMapping>(shadow_map::readSingleView(args), o);
}

}  // namespace penumbra
