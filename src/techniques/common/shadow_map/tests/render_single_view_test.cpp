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

}  // namespace
}  // namespace penumbra::test
