// dcs's parameters and its wedge paths at scale: the variants are dcs with
// parameters, the fill profile counts what reaches the wedge shader, the compute path and the
// raster path's cut solids give the same (pixel, edge) pairs and per-sample results.
#include "render_test_util.h"

#include "gl/statistics.h"
#include "scene/loaders.h"
#include "techniques/dcs/wedge_geometry.h"

namespace penumbra::test {
namespace {

// dcs's options through --param. The variants are presets of the same declarations,
// so `dcs` with a variant's parameters renders the variant's image exactly.
TEST(DcsParams, VariantsAreDcsWithParameters) {
  Scene scene = loadScene(scenePath("scenes/stained-glass.json"));
  RenderSettings s = settings(48, 8);
  for (auto [variant, param] : {std::pair{"dcs-standard", "silhouettes=standard"}, std::pair{"dcs-sum", "opacity=sum"},
                                std::pair{"dcs-lut", "coverage=lut"}}) {
    auto a = makeTechnique(variant);
    auto b = makeTechnique("dcs", params({param}));
    FrameResult fa = Renderer(context(), scene, s).render(*a);
    FrameResult fb = Renderer(context(), scene, s).render(*b);
    EXPECT_EQ(compareImages(fa.lights[0].visibility, fb.lights[0].visibility).maxAbs, 0.0) << variant;
    EXPECT_EQ(statistic(fa, "coverageMode"), statistic(fb, "coverageMode")) << variant;
  }
  // targets=1 splits the samples over more passes, exact all the same.
  auto narrow = makeTechnique("dcs", params({"targets=1", "min-base=4096"}));
  FrameResult f = Renderer(context(), scene, s).render(*narrow);
  EXPECT_EQ(statistic(f, "targets"), 1.0);
  EXPECT_EQ(statistic(f, "counterBase"), 4096.0);
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// The profile (the fill measure) changes nothing in the image, and counts what reaches
// the wedge shader after the depth test: with its atomic counters the test would otherwise run
// after the shader and every rasterised fragment would be counted (476 M on the engine at 256 px
// against 28.5 M reaching the shader). On the default scene at 96 px: every count below the
// rasterised fragments the pipeline statistics see, and each stage of the shader's tests keeps
// fewer.
TEST(DcsProfile, CountsTheFragmentsThatReachTheShader) {
  const Scene scene = defaultScene();
  RenderSettings s = settings(96, 16);
  auto plain = makeTechnique("dcs");
  auto profiled = makeTechnique("dcs", params({"profile=1"}));
  FrameResult a = Renderer(context(), scene, s).render(*plain);
  FrameResult b = Renderer(context(), scene, s).render(*profiled);
  EXPECT_EQ(compareImages(a.lights[0].visibility, b.lights[0].visibility).maxAbs, 0.0);
  const double fragments = statistic(b, "profileFragments"), inPlane = statistic(b, "profileInPlane");
  const double weighted = statistic(b, "profileWeighted"), updating = statistic(b, "profileUpdating");
  std::printf("fragments %.0f, in plane %.0f, weighted %.0f, updating %.0f\n", fragments, inPlane, weighted, updating);
  EXPECT_GT(updating, 0.0);
  EXPECT_LE(updating, weighted);
  EXPECT_LE(weighted, inPlane);
  EXPECT_LE(inPlane, fragments);
  if (gl::PipelineStatistics::supported()) {
    double rasterised = 0.0;
    for (auto& st : b.timer.stages())
      if (st.stage == "dcs wedges" && st.counted) rasterised = double(st.counts.fragmentInvocations);
    std::printf("fragment invocations of the wedge stage (pipeline statistics): %.0f\n", rasterised);
    if (rasterised > 0.0) {
      EXPECT_LT(fragments, 0.5 * rasterised) << "the profile counted fragments that fail the depth test";
    }
  }
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

}  // namespace
}  // namespace penumbra::test

namespace penumbra::test {
namespace {

// The compute path (wedges binned into tiles, evaluated per pixel inside the solid)
// gives the raster path's per-sample results: the same visibility, the same updating (pixel,
// edge) pairs where the profile counts them, and its bound is the true maximum count (it packs
// the final counts only, no bound pass). Semi-opaque occluders (counts, not just their sign),
// path crossings, 64 samples over several targets, and the engine's 66,654 edges at 64 px (the
// dispatches in chunks: one long loop was cut short by llvmpipe).
struct ComputePathCase {
  const char* scene;
  int samples, size;
};
class DcsComputePath : public ::testing::TestWithParam<ComputePathCase> {};

TEST_P(DcsComputePath, EqualsTheRasterPathAndTheReference) {
  const auto [scene, samples, size] = GetParam();
  const Scene sc = *scene ? loadScene(scenePath(scene)) : defaultScene();
  Comparison c = renderAndCompare(sc, "dcs", settings(size, samples), params({"path=compute", "profile=1"}));
  auto raster = makeTechnique("dcs", params({"profile=1"}));
  FrameResult r = Renderer(context(), sc, settings(size, samples)).render(*raster);
  EXPECT_EQ(compareImages(c.frame.lights[0].visibility, r.lights[0].visibility).maxAbs, 0.0);
  EXPECT_EQ(c.errors.sampleMismatches, 0);
  EXPECT_EQ(statistic(c.frame, "negativeCountPixels"), 0.0);
  EXPECT_EQ(statistic(c.frame, "inconsistentPixels"), 0.0);
  EXPECT_EQ(statistic(c.frame, "boundMaxCount"), statistic(c.frame, "maxCount"));
  // The same (pixel, edge) pairs on every scene. Until the cut solids the raster path found a
  // few more on the built-in scene (96 px: llvmpipe 2, 256 px: 10): one thin wedge under a
  // light spanning nearly a half-space had a cap whose corners crossed and covered a pixel
  // three times; such a polyhedron is no longer drawn (dcs_wedge.geom, orientedAsFacing), and
  // a fold of a sliver face counts with its sign (engine, 64 px: one pair).
  EXPECT_EQ(statistic(c.frame, "maxCount"), statistic(r, "maxCount"));
  EXPECT_EQ(statistic(c.frame, "profileUpdating"), statistic(r, "profileUpdating"));
  EXPECT_EQ(statistic(c.frame, "profileWeighted"), statistic(r, "profileWeighted"));
  EXPECT_LE(statistic(c.frame, "profileFragments"), statistic(c.frame, "profileCandidates"));
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

INSTANTIATE_TEST_SUITE_P(Scenes, DcsComputePath,
                         ::testing::Values(ComputePathCase{"", 16, 96},
                                           ComputePathCase{"scenes/stained-glass.json", 16, 96},
                                           ComputePathCase{"scenes/hard/15-two-plates.json", 64, 64},
                                           ComputePathCase{"scenes/hard/28-rect-partly-inside.json", 16, 64},
                                           ComputePathCase{"scenes/engine.json", 16, 64}),
                         [](const ::testing::TestParamInfo<ComputePathCase>& i) {
                           return (*i.param.scene ? sceneTestName(i.param.scene) : std::string("default")) + "_N" +
                                  std::to_string(i.param.samples);
                         });

// The raster path: the wedge solids cut by their end cones' planes and
// the view reach fewer surfaces (engine, 64 px: 0.56 M fragments against 1.82 M without the end
// planes, measured 2026-12-06), with the same per-sample results and the same (pixel, edge) pairs.
TEST(DcsRasterPath, EndPlanesCutTheFillNotTheResult) {
  const Scene sc = loadScene(scenePath("scenes/engine.json"));
  auto cut = makeTechnique("dcs", params({"profile=1"}));
  auto loose = makeTechnique("dcs", params({"profile=1", "end-planes=0"}));
  Renderer renderer(context(), sc, settings(64, 16));
  FrameResult a = renderer.render(*cut), b = renderer.render(*loose);
  EXPECT_EQ(compareImages(a.lights[0].visibility, b.lights[0].visibility).maxAbs, 0.0);
  EXPECT_EQ(statistic(a, "profileUpdating"), statistic(b, "profileUpdating"));
  EXPECT_EQ(statistic(a, "profileWeighted"), statistic(b, "profileWeighted"));
  EXPECT_LT(statistic(a, "profileFragments"), 0.5 * statistic(b, "profileFragments"));
  std::printf("engine 64 px: fragments %.0f (end planes) vs %.0f, updating %.0f\n", statistic(a, "profileFragments"),
              statistic(b, "profileFragments"), statistic(a, "profileUpdating"));
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// Scenes past one storage block (wedge_geometry.h): the edge table in bands of at most the
// given bytes, each edge's incidences in its own band and counted from the band's first, the
// bands in order and covering every edge; the same edges and incidences as one band.
TEST(DcsBands, EveryBandFitsAndItsIncidencesCountFromItsOwn) {
  ShadowVolumeCounter::MeshVolumes m;
  m.topology = geo::buildEdgeTopology(detail::makeSphere(1.0f, 64, 48));
  m.rule = geo::volumeRuleFor(m.topology);
  const dcs::EdgeTable one = dcs::buildEdgeTable({m}, 0), many = dcs::buildEdgeTable({m}, 65536);
  ASSERT_EQ(one.bands.size(), 1u);
  ASSERT_GE(many.bands.size(), 4u);
  ASSERT_EQ(one.edges.size(), many.edges.size());
  std::uint32_t next = 0;
  for (const dcs::EdgeBand& b : many.bands) {
    EXPECT_EQ(b.firstEdge, next);
    next = b.endEdge;
    EXPECT_LE((b.endEdge - b.firstEdge) * sizeof(dcs::GpuEdge), 65536u);
    EXPECT_LE((b.endIncidence - b.firstIncidence) * sizeof(dcs::GpuIncidence), 65536u);
    for (std::uint32_t e = b.firstEdge; e < b.endEdge; ++e) {
      const glm::ivec4 a = one.edges[e].meta, c = many.edges[e].meta;
      EXPECT_EQ(std::uint32_t(c.x) + b.firstIncidence, std::uint32_t(a.x));
      EXPECT_LE(b.firstIncidence + std::uint32_t(c.x + c.y), b.endIncidence);
      EXPECT_EQ(many.bandOf(e), std::size_t(&b - many.bands.data()));
    }
  }
  EXPECT_EQ(next, std::uint32_t(one.edges.size()));
}

// With band-bytes forced to 64 KiB, the smallest, the 729 spheres' 52 k edges go in 52 bands
// (stained glass's semi-opaque panes in 4) and the shadow-volume count's faces in several; each
// band bound and drawn on its own gives the counts of one band: dcs equals raytrace per sample
// outside the edge band and its one-band image exactly, on the raster path with the CPU's
// silhouettes and on the compute path with the GPU's.
TEST(DcsBands, ASceneInManyBandsRendersAsInOne) {
  const RenderSettings s = settings(64, 16);
  const std::string band = "band-bytes=65536";
  struct Case {
    const char* scene;
    std::vector<std::string> extra;
    double bands;  // at least
  };
  for (const Case& c : {Case{"scenes/hard/15-sphere-grid.json", {}, 40.0},
                        Case{"scenes/hard/15-sphere-grid.json", {"path=compute", "gpu-silhouettes=1"}, 40.0},
                        Case{"scenes/stained-glass.json", {}, 3.0}}) {
    const Scene scene = loadScene(scenePath(c.scene));
    std::vector<std::string> whole = c.extra, split = c.extra;
    split.push_back(band);
    const std::string what = std::string(c.scene) + (c.extra.empty() ? "" : " " + c.extra.front());
    const Comparison banded = renderAndCompare(scene, "dcs", s, params(split));
    std::printf("%s: edge bands %.0f\n", what.c_str(), statistic(banded.frame, "edgeBands"));
    EXPECT_GE(statistic(banded.frame, "edgeBands"), c.bands) << what;
    EXPECT_EQ(banded.errors.sampleMismatches, 0) << what << ": " << banded.errors.samplePairs << " pairs compared";
    EXPECT_LE(banded.errors.visibilityOutsideBand.rmse, 1e-3) << what;
    EXPECT_EQ(statistic(banded.frame, "negativeCountPixels"), 0.0) << what;
    const FrameResult one = Renderer(context(), scene, s).render(*makeTechnique("dcs", params(whole)));
    EXPECT_EQ(statistic(one, "edgeBands"), 1.0) << what;
    EXPECT_EQ(statistic(one, "edges"), statistic(banded.frame, "edges")) << what;
    EXPECT_EQ(compareImages(one.lights[0].visibility, banded.frame.lights[0].visibility).maxAbs, 0.0) << what;
    EXPECT_TRUE(one.lights[0].perSample == banded.frame.lights[0].perSample) << what;
  }
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

}  // namespace
}  // namespace penumbra::test
