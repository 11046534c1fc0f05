// Real assets rendered: compressed glTF shadows as its uncompressed original does, and the
// exact technique equals the reference on a scene of compressed models from the wild.
#include <cmath>

#include "core/metrics.h"
#include "render_test_util.h"

namespace penumbra::test {
namespace {

// The Draco engine (11-bit positions) against the uncompressed file it was made from, in the
// engine scene, both with the reference's rays: the visibility differs only where a pixel sees
// the quantization (within a pixel of a shadow edge or of a silhouette, where the G-buffers
// disagree), and not by more than the light samples a moved edge can cover.
TEST(Assets, DracoEngineShadowsAsTheUncompressed) {
  const char* assimp = "/usr/share/assimp/models/glTF2/draco/2CylinderEngine.gltf";
  if (!std::filesystem::exists(assimp)) FAIL() << "assimp-testmodels not installed (./setup.sh --deps installs it)";
  const Scene plain = loadScene(scenePath("scenes/engine.json"));
  const Scene draco =
      loadScene(scenePath("scenes/engine.json"), {"objects.1.file=\"assimp:glTF2/draco/2CylinderEngine.gltf\""});
  const RenderSettings s = settings(128, 8);
  auto ray = makeTechnique("raytrace");
  Renderer a(context(), plain, s);
  const FrameResult p = a.render(*ray, "raytrace");
  Renderer b(context(), draco, s);
  const FrameResult d = b.render(*ray, "raytrace");
  ASSERT_EQ(p.lights.size(), 1u);
  // Pixels both G-buffers hit, away from the uncompressed file's silhouettes (where the two
  // G-buffers may see different surfaces) and shadow edges.
  const int w = s.width, h = s.height;
  ASSERT_TRUE(p.gbuffer.camera.has_value());
  const glm::vec3 eye = *p.gbuffer.camera;
  std::vector<std::uint8_t> both(std::size_t(w * h), 0), band = edgeBandMask(p.lights[0].visibility, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y * w + x);
      both[i] = p.gbuffer.valid[i] && d.gbuffer.valid[i];
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = std::clamp(x + dx, 0, w - 1), v = std::clamp(y + dy, 0, h - 1);
          const std::size_t j = std::size_t(v * w + u);
          if (p.gbuffer.valid[j] != p.gbuffer.valid[i] ||
              glm::distance(p.gbuffer.position[j], p.gbuffer.position[i]) >
                  0.03f * glm::distance(p.gbuffer.position[i], eye))
            band[i] = 1;
        }
    }
  const ErrorStats all = compareImages(d.lights[0].visibility, p.lights[0].visibility, {}, both);
  const ErrorStats outside = compareImages(d.lights[0].visibility, p.lights[0].visibility, band, both);
  std::printf("draco engine against the uncompressed: %lld of %lld pixels differ (max %.3f); outside the edge and "
              "silhouette band %lld of %lld (max %.3f)\n",
              (long long)all.pixelsOver, (long long)all.pixelsCounted, all.maxAbs, (long long)outside.pixelsOver,
              (long long)outside.pixelsCounted, outside.maxAbs);
  EXPECT_GT(outside.pixelsCounted, w * h / 4);
  EXPECT_LE(outside.maxAbs, 1e-6);  // the same rays, the same hits: equal
  EXPECT_LE(all.pixelsOver, all.pixelsCounted / 100);
}

// dcs equals the reference per light sample on the Draco CC0 models (outside the 1-pixel band).
TEST(Assets, DcsIsExactOnTheDracoModels) {
  const Scene scene = loadScene(scenePath("scenes/cc0-draco.json"));
  const Comparison c = renderAndCompare(scene, "dcs", settings(96, 16));
  std::printf("cc0-draco dcs: visibility RMSE %.5f outside the band, %lld misclassified\n",
              c.errors.visibilityOutsideBand.rmse, (long long)c.errors.misclassifiedPixels);
  EXPECT_GT(c.errors.visibilityOutsideBand.pixelsCounted, 1000);
  EXPECT_LE(c.errors.visibilityOutsideBand.maxAbs, 1e-6);
  EXPECT_EQ(c.errors.misclassifiedPixels, 0);
}

}  // namespace
}  // namespace penumbra::test
