// `pcss` against the Embree reference with the same light samples. PCSS is a
// single-view approximation: its error is measured with explicit tolerances, and its known
// failures (occluder fusion, VWSS paper Fig. 10) must show in the comparison.
#include "render_test_util.h"

namespace penumbra::test {
namespace {

// Hard case 23 (square occluder parallel under a square light): the parallel-planes estimate
// holds; the filtered result is within 0.02 RMSE of ray tracing (measured 0.019 / 0.017 at N =
// 16, 0.012 for Ultra at N = 64).
TEST(Pcss, ParallelPlanesCaseMatchesTheReference) {
  Scene scene = loadScene(scenePath("scenes/hard/23-analytic-square.json"));
  Comparison sterna = renderAndCompare(scene, "pcss", settings(128, 64));
  Comparison ultra = renderAndCompare(scene, "pcss-ultra", settings(128, 64));
  RecordProperty("rmse_pcss", std::to_string(sterna.errors.visibility.rmse));
  RecordProperty("rmse_pcss_ultra", std::to_string(ultra.errors.visibility.rmse));
  EXPECT_LE(sterna.errors.visibility.rmse, 0.025);
  EXPECT_LE(ultra.errors.visibility.rmse, 0.02);
  // More samples, less noise.
  EXPECT_LT(ultra.errors.visibility.rmse, sterna.errors.visibility.rmse);
  EXPECT_EQ(statistic(ultra.frame, "blocker samples"), 64.0);
  EXPECT_EQ(statistic(ultra.frame, "pcf samples"), 96.0);
}

// Occluder fusion (hard case 15, two plates at different heights): one depth per texel and one
// average blocker depth cannot represent both plates; multi-view methods can.
TEST(Pcss, OccluderFusionFailureShows) {
  Scene scene = loadScene(scenePath("scenes/hard/15-two-plates.json"));
  double pcss = renderAndCompare(scene, "pcss-ultra", settings(128, 16)).errors.visibility.rmse;
  double mvr = renderAndCompare(scene, "mvr", settings(128, 16)).errors.visibility.rmse;
  RecordProperty("rmse_pcss_ultra", std::to_string(pcss));
  RecordProperty("rmse_mvr", std::to_string(mvr));
  EXPECT_GE(pcss, 2.5 * mvr);
  EXPECT_LE(pcss, 0.08);
}

// Where nothing blocks the light, pcss is lit unless its blocker search (over the light's
// footprint on the nearest occluder's plane, a wider region than the light's true cone) finds
// an occluder nearby: the mean error there stays small. The textured light is modulated by its
// mean luminance (in penumbrae the reference weighs each sample's colour).
TEST(Pcss, UnblockedPixelsStayLitAndTexturedLightsAverage) {
  Scene scene = loadScene(scenePath("scenes/stained-glass.json"));
  Comparison r = renderAndCompare(scene, "pcss", settings(128, 16));
  const Image& v = r.frame.lights[0].visibility;
  const Image& ref = r.reference.lights[0].visibility;
  const auto& per = r.reference.lights[0].perSample;
  const int n = r.reference.lights[0].samples;
  std::size_t unblocked = 0, exact = 0;
  double errorSum = 0.0;
  for (std::size_t px = 0; px < r.reference.gbuffer.valid.size(); ++px) {
    if (!r.reference.gbuffer.valid[px]) continue;
    bool all = true;
    for (int k = 0; k < n; ++k) all = all && per[px * std::size_t(n) + std::size_t(k)] == 1.0f;
    if (!all) continue;
    ++unblocked;
    double e = 0.0;
    for (int c = 0; c < 3; ++c) e += std::abs(v.data[px * 3 + c] - ref.data[px * 3 + c]) / 3.0;
    errorSum += e;
    exact += e < 1e-4;
  }
  ASSERT_GT(unblocked, 1000u);
  RecordProperty("unblocked_exact_fraction", std::to_string(double(exact) / double(unblocked)));
  EXPECT_GE(double(exact), 0.8 * double(unblocked));
  EXPECT_LE(errorSum / double(unblocked), 0.01);
  EXPECT_LE(r.errors.visibility.rmse, 0.04);
}

TEST(Pcss, SampleCountsAndSemiOpaqueAreReported) {
  Comparison r = renderAndCompare(loadScene(scenePath("scenes/semi-opaque.json")), "pcss", settings(64, 4),
                                  params({"blocker-samples=8", "pcf-samples=4", "map=256"}));
  EXPECT_EQ(statistic(r.frame, "blocker samples"), 8.0);
  EXPECT_EQ(statistic(r.frame, "pcf samples"), 4.0);
  EXPECT_EQ(statistic(r.frame, "map size"), 256.0);
  EXPECT_GT(statistic(r.frame, "semi-opaque triangles as opaque"), 0.0);
}

// Sterna's cheaper penumbra estimates stay close to the per-pixel blocker search on the parallel
// planes case (measured RMSE 0.018-0.024 against the reference at N = 16).
TEST(PcssVariants, MaskMinFilterAndCheckerboardStayClose) {
  Scene scene = loadScene(scenePath("scenes/hard/23-analytic-square.json"));
  Renderer renderer(context(), scene, settings(128, 16));
  auto ref = makeTechnique("raytrace");
  FrameResult reference = renderer.render(*ref);
  for (const char* name : {"pcss-mask", "pcss-minfilter", "pcss-checker", "pcss-dense"}) {
    auto t = makeTechnique(name);
    FrameResult f = renderer.render(*t);
    double rmse = measureErrors(f, reference).visibility.rmse;
    RecordProperty(std::string("rmse_") + name, std::to_string(rmse));
    EXPECT_LE(rmse, 0.03) << name;
  }
  // The mask's options are read and reported.
  auto one = makeTechnique("pcss-mask", TechniqueParams({"no-blocker-one=1", "kernel-scale=1.2", "blur=0"}));
  FrameResult f = renderer.render(*one);
  EXPECT_DOUBLE_EQ(statistic(f, "kernel scale"), 1.2);
  EXPECT_LE(measureErrors(f, reference).visibility.rmse, 0.05);
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// Hard cases 16 (contact) and 18 (receiver grazed at 1 degree): the slope-scaled bias
// (shadow_map_common.glsl biasedDepth) keeps lit surfaces lit (acne: decisions differing from
// the reference outside the edge band) without opening lit gaps in umbrae (peter-panning: the
// reference's fully shadowed pixels that come out more than half lit).
struct BiasCase {
  const char* scene;
  const char* technique;
};
class DepthBias : public ::testing::TestWithParam<BiasCase> {};

TEST_P(DepthBias, NoAcneNoPeterPanning) {
  const BiasCase& c = GetParam();
  Comparison r = renderAndCompare(loadScene(scenePath(c.scene)), c.technique, settings(128, 16));
  const auto& e = r.errors;
  double acne = misclassifiedFraction(e);
  const auto& per = r.reference.lights[0].perSample;
  const int n = r.reference.lights[0].samples;
  const Image& v = r.frame.lights[0].visibility;
  std::size_t umbra = 0, leaked = 0;
  for (std::size_t px = 0; px < r.reference.gbuffer.valid.size(); ++px) {
    if (!r.reference.gbuffer.valid[px]) continue;
    bool dark = true;
    for (int k = 0; k < n && dark; ++k) dark = per[px * std::size_t(n) + std::size_t(k)] == 0.0f;
    if (!dark) continue;
    ++umbra;
    leaked += v.data[px * 3] > 0.5f;
  }
  RecordProperty("acne_fraction", std::to_string(acne));
  RecordProperty("umbra_leak_fraction", std::to_string(umbra ? double(leaked) / double(umbra) : 0.0));
  EXPECT_LE(acne, 0.01);
  ASSERT_GT(umbra, 100u) << "no umbra in view";
  EXPECT_LE(double(leaked), 0.02 * double(umbra)) << leaked << " of " << umbra << " umbra pixels lit";
}

INSTANTIATE_TEST_SUITE_P(Scenes, DepthBias,
                         ::testing::Values(BiasCase{"scenes/hard/16-contact.json", "mvr"},
                                           BiasCase{"scenes/hard/16-contact.json", "pcss"},
                                           BiasCase{"scenes/hard/18-grazing-receiver.json", "mvr"},
                                           BiasCase{"scenes/hard/18-grazing-receiver.json", "pcss"},
                                           BiasCase{"scenes/hard/16-contact.json", "vssm"},
                                           BiasCase{"scenes/hard/18-grazing-receiver.json", "vssm"}),
                         [](const auto& info) { return sceneTestName(info.param.scene) + "_" + info.param.technique; });

// Thin geometry missed by the blocker search (VWSS paper Fig. 10): a 1 cm blade high under a
// large light. Its texels fall between the search's taps at many pixels, so pcss leaves holes and
// noise where the same-sample reference has the blade's 16 thin hard shadows (measured RMSE 0.019
// against mvr's 0.008, 2026-12-01; against the converged reference, which has no 16-sample
// banding either, both are 0.012: docs/results/single-map.md).
TEST(Pcss, ThinBladeMissedByTheBlockerSearch) {
  Scene scene = loadScene(scenePath("scenes/hard/15-thin-blade.json"));
  double pcss = renderAndCompare(scene, "pcss", settings(128, 16)).errors.visibility.rmse;
  double mvr = renderAndCompare(scene, "mvr", settings(128, 16)).errors.visibility.rmse;
  RecordProperty("rmse_pcss", std::to_string(pcss));
  RecordProperty("rmse_mvr", std::to_string(mvr));
  EXPECT_GE(pcss, 1.8 * mvr);
  EXPECT_LE(pcss, 0.04);
}

}  // namespace
}  // namespace penumbra::test
