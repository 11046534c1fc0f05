// The single-map framework (src/techniques/common/shadow_map) on the analytic hard cases:
// pcss-ultra and vssm against the converged reference.
#include "render_test_util.h"

namespace penumbra::test {
namespace {

// Hard case 23 against the converged reference (2048 stratified samples a pixel, which stands
// for the closed form): the filtered single-view methods are within 0.02 (the hard-case table's
// tolerance for filtered methods); they do not depend on the light samples, so this is their
// fair comparison.
TEST(SingleView, AnalyticCasesAgainstTheConvergedReference) {
  for (const char* path : {"scenes/hard/23-analytic-square.json", "scenes/hard/23-analytic-disk.json"}) {
    Scene scene = loadScene(scenePath(path));
    Renderer renderer(context(), scene, settings(128, 64));
    auto converged = convergedReference();
    FrameResult ref = renderer.render(*converged);
    for (const char* name : {"pcss-ultra", "vssm"}) {
      auto t = makeTechnique(name);
      double rmse = measureErrors(renderer.render(*t), ref).visibility.rmse;
      RecordProperty(sceneTestName(path) + "_" + name, std::to_string(rmse));
      EXPECT_LE(rmse, 0.02) << path << " " << name;
    }
  }
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// Contact shadows (common/shadow_map/contact.h) on hard case 16 with a coarse map (128^2), where
// the map's texels are too wide for the box's and the stacked plates' contacts: the march adds
// the contact shadow and the error falls (measured RMSE pcss 0.0474 -> 0.0453, smrt-unclamped
// 0.0483 -> 0.0459). Under the analytic plate (hard case 23, 1.5 units above the floor) the
// march (5% of the screen) meets nothing, so the image is pcss's to float rounding.
TEST(ContactShadows, DarkenContactsAndNothingElse) {
  Scene contact = loadScene(scenePath("scenes/hard/16-contact.json"));
  for (const char* name : {"pcss", "smrt-unclamped"}) {
    const double without =
        renderAndCompare(contact, name, settings(128, 16), params({"map=128"})).errors.visibility.rmse;
    const Comparison with = renderAndCompare(contact, name, settings(128, 16), params({"map=128", "contact=1"}));
    RecordProperty(std::string(name) + "_without_with",
                   std::to_string(without) + " " + std::to_string(with.errors.visibility.rmse));
    EXPECT_LT(with.errors.visibility.rmse, 0.98 * without) << name;
    EXPECT_EQ(statistic(with.frame, "contact shadows"), 1.0);
    EXPECT_EQ(statistic(with.frame, "contact steps"), 8.0);
  }
  Scene plate = loadScene(scenePath("scenes/hard/23-analytic-square.json"));
  const Comparison pcss = renderAndCompare(plate, "pcss", settings(128, 16));
  const Comparison pcssContact = renderAndCompare(plate, "pcss-contact", settings(128, 16));
  const Image& a = pcss.frame.lights[0].visibility;
  const Image& b = pcssContact.frame.lights[0].visibility;
  ASSERT_EQ(a.data.size(), b.data.size());
  float worst = 0.0f;
  for (std::size_t i = 0; i < a.data.size(); ++i) worst = std::max(worst, std::abs(a.data[i] - b.data[i]));
  EXPECT_LE(worst, 1e-6f);
}

}  // namespace
}  // namespace penumbra::test
