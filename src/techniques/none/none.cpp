// `none`: unshadowed. Visibility is 1 for every sample above the surface's horizon (eq. 2 with
// D = 0), so shading equals the other techniques' wherever they see the whole light.
#include "techniques/none/none.h"

#include "gl/objects.h"
#include "pipeline/renderer.h"
#include "shared/shared.h"  // NOLINT: shared with GLSL

namespace penumbra {
namespace {

class Unshadowed final : public Technique {
 public:
  void prepare(const Scene&, GpuScene&) override {
    resolve_ = gl::Program({"fullscreen.vert", "pipeline_resolve.frag"}, {"UNSHADOWED"});
  }
  void renderVisibility(LightPass& pass) override {
    pass.timer.time("resolve", [&] { resolveVisibility(pass, resolve_); });
  }

 private:
  gl::Program resolve_;
};

}  // namespace

std::unique_ptr<Technique> makeUnshadowed() { return std::make_unique<Unshadowed>(); }

}  // namespace penumbra
