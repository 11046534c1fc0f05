#include "techniques/vssm/vssm.h"

#include <algorithm>
#include <cmath>

#include "pipeline/renderer.h"
#include "sampling/shared.hpp"
#include "techniques/shadow_map/single_view.h"

namespace penumbra {
namespace {

class VarianceSoftShadowMapping final : public shadow_map::SingleViewTechnique {
 public:
  VarianceSoftShadowMapping(const shadow_map::MapOptions& m, const VssmOptions& o)
      : SingleViewTechnique(o.exactSat ? "vssm" : "vssm-fp32", m), o_(o) {}

 protected:
  void renderShadow(LightPass& pass) override {
    const auto& f = frame();
    // Depth range of the moments: from the nearest occluder to the farthest scene point ahead.
    glm::vec3 lo, hi;
    pass.scene.bounds(lo, hi);
    float far = 0.0f;
    for (int c = 0; c < 8; ++c) {
      glm::vec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
      far = std::max(far, glm::dot(corner - pass.light.position, f.axis));
    }
    depthMin_ = std::min(searchNear(), far);
    depthMax_ = std::max(far, depthMin_ * 1.001f + 1e-6f);
    // Threshold = 1e-4 r (section 6), r the scene's bounding radius, in normalised depth.
    const float radius = 0.5f * glm::length(hi - lo);
    threshold_ = float(std::pow(1e-4 * radius / (depthMax_ - depthMin_), 2.0));

    pass.timer.time(name() + " sat", [&] {
      const std::size_t texels = std::size_t(f.size) * std::size_t(f.size);
      const std::size_t bytes = texels * (o_.exactSat ? 16 : 8);
      if (sat_.size() != bytes) sat_ = gl::Buffer(bytes, nullptr);
      sat_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_VSSM_SAT);
      const gl::Program& p = program("sat", {"vssm_sat.comp"}, o_.exactSat ? std::vector<std::string>{"EXACT"}
                                                                            : std::vector<std::string>{});
      p.set("satSize", f.size);
      p.set("mapNear", f.zNear);
      p.set("depthMin", depthMin_);
      p.set("depthMax", depthMax_);
      p.use();
      for (int pass3 = 0; pass3 < 3; ++pass3) {
        p.set("pass", pass3);
        std::size_t threads = pass3 == 0 ? texels : std::size_t(f.size);
        glDispatchCompute(GLuint((threads + PENUMBRA_MAP_LOCAL_SIZE - 1) / PENUMBRA_MAP_LOCAL_SIZE), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
      }
    });
    pass.timer.time(name() + " shadow pass", [&] {
      const gl::Program& p = program("resolve", {"fullscreen.vert", "vssm_resolve.frag"},
                                     o_.exactSat ? std::vector<std::string>{"EXACT"} : std::vector<std::string>{});
      setUniforms(p, pass, 0, 0, 1.0);
      p.set("depthMin", depthMin_);
      p.set("depthMax", depthMax_);
      p.set("blockerDiv", o_.blockerDiv);
      p.set("shadowDiv", o_.shadowDiv);
      p.set("threshold", threshold_);
      sat_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_VSSM_SAT);
      bindMap();
      resolveVisibility(pass, p);
    });
  }

  std::size_t extraBytes() const override { return sat_.size(); }

  void addStatistics(std::vector<std::pair<std::string, double>>& out) const override {
    out.emplace_back("exact sat", o_.exactSat ? 1.0 : 0.0);
    out.emplace_back("blocker sub-kernels", double(o_.blockerDiv * o_.blockerDiv));
    out.emplace_back("shadow sub-kernels", double(o_.shadowDiv * o_.shadowDiv));
    out.emplace_back("depth min", depthMin_);
    out.emplace_back("depth max", depthMax_);
    out.emplace_back("sat bytes", double(sat_.size()));
  }

 private:
  VssmOptions o_;
  gl::Buffer sat_;
  float depthMin_ = 0.0f, depthMax_ = 1.0f, threshold_ = 0.0f;
};

}  // namespace

std::unique_ptr<Technique> makeVarianceSoftShadowMapping(const TechniqueParams& params, VssmOptions o) {
  o.blockerDiv = params.getInt("blocker-div", o.blockerDiv, 1, 16);
  o.shadowDiv = params.getInt("shadow-div", o.shadowDiv, 1, 16);
  return std::make_unique<VarianceSoftShadowMapping>(shadow_map::readMapOptions(params), o);
}

}  // namespace penumbra
