// `hard-sv`: hard shadows from the light centre: the z-fail shadow-volume count of
// techniques/common/shadow_volume/ resolved to visibility (0 volumes around the point: lit).
#include "techniques/hard_sv/hard_sv.h"

#include "core/log.h"
#include "gl/objects.h"
#include "pipeline/renderer.h"
#include "shared/shared.h"  // NOLINT: shared with GLSL
#include "techniques/common/shadow_volume/shadow_volume.h"

namespace penumbra {
namespace {

class HardShadowVolumes final : public Technique {
 public:
  explicit HardShadowVolumes(std::size_t bandBytes) { volumes_.setBandBytes(bandBytes); }

  void prepare(const Scene& scene, GpuScene& gpu) override {
    if (scene.hasSemiOpaque())
      PLOG_WARN("hard-sv treats semi-opaque occluders as opaque (its error against the reference says how much)");
    volumes_.prepare(scene, gpu);
    resolve_ = gl::Program({"fullscreen.vert", "pipeline_resolve.frag"}, {"COUNTER"});
  }

  void renderVisibility(LightPass& pass) override {
    // The hard shadow of the centre: its placement alone decides the closed meshes' rule.
    const ShadowVolumeCounter::Placement placed =
        volumes_.place(glm::dvec3(pass.light.position), nullptr, 0.0, glm::dvec3(pass.gpu.cameraPosition()));
    perTriangleMeshes_ = placed.perTriangleMeshes;
    volumes_.count(pass, placed.rules);
    pass.timer.time("resolve", [&] {
      volumes_.counter().bind(PENUMBRA_UNIT_COUNTER);
      resolveVisibility(pass, resolve_);
    });
  }

  std::size_t memoryBytes() const override { return volumes_.bytes(); }
  bool seesAlphaTest() const override { return false; }  // volumes from the meshes' edges

  std::vector<std::pair<std::string, double>> statistics() const override {
    return {{"closedMeshesPerTriangle", double(perTriangleMeshes_)},
            {"volumeSides", double(volumes_.sideEdges())},
            {"volumeCaps", double(volumes_.caps())},
            {"volumeCoverTriangles", double(volumes_.coverTriangles())},
            {"volumeBands", double(volumes_.bands())}};
  }

 private:
  ShadowVolumeCounter volumes_;
  gl::Program resolve_;
  std::size_t perTriangleMeshes_ = 0;
};

}  // namespace

std::unique_ptr<Technique> makeHardShadowVolumes(std::size_t bandBytes) {
  return std::make_unique<HardShadowVolumes>(bandBytes);
}

}  // namespace penumbra
