// The multi-view shadow-map techniques (mvr, vwss, reproject) against the Embree
// reference with the same light samples, and against each other. Shadow maps are approximate:
// per-(pixel, sample) decisions are gated outside the 1-pixel edge band with explicit
// tolerances, measured on this machine at 128 px and N = 16 (docs/techniques/multi-view.md).
#include "render_test_util.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "gl/objects.h"
#include "pipeline/enclosure.h"
#include "shared/shared.h"  // NOLINT: shared with GLSL
#include "techniques/common/shadow_map/maps.h"
#include "techniques/common/shadow_map/shaders/shadow_map_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra::test {
namespace {

double maxPerSampleDifference(const FrameResult& a, const FrameResult& b) {
  EXPECT_EQ(a.lights[0].perSample.size(), b.lights[0].perSample.size());
  double d = 0.0;
  for (std::size_t i = 0; i < std::min(a.lights[0].perSample.size(), b.lights[0].perSample.size()); ++i)
    d = std::max(d, double(std::abs(a.lights[0].perSample[i] - b.lights[0].perSample[i])));
  return d;
}

struct Case {
  const char* scene;
  const char* technique;
  double minAgreement;  // per-(pixel, sample) decisions outside the edge band
  double maxRmse;       // visibility buffer, all surface pixels
};

class MultiViewVsRaytrace : public ::testing::TestWithParam<Case> {};

TEST_P(MultiViewVsRaytrace, PerSampleDecisionsOutsideEdgeBand) {
  const Case& c = GetParam();
  const Scene scene = loadScene(scenePath(c.scene));
  Comparison r = renderAndCompare(scene, c.technique, settings(128, 16));
  const auto& e = r.errors;
  ASSERT_GT(e.samplePairs, 0);
  RecordProperty("sample_agreement", std::to_string(e.sampleAgreement));
  RecordProperty("visibility_rmse", std::to_string(e.visibility.rmse));
  EXPECT_GE(e.sampleAgreement, c.minAgreement) << e.samplePairs << " pairs";
  EXPECT_LE(e.visibility.rmse, c.maxRmse);
  // Left unshadowed and counted: the surface behind a one-sided light (which it does not light;
  // hard case 22's box above the light) and the receivers just below the light's plane beside it
  // (its crossing box) that would need a frustum wider than max-angle; those are few.
  const Light& light = scene.lights[0];
  const bool oneSided = light.shape == LightShape::Rect || light.shape == LightShape::Disk;
  std::int64_t behind = 0;
  for (std::size_t i = 0; i < r.frame.gbuffer.valid.size(); ++i)
    behind += oneSided && r.frame.gbuffer.valid[i] &&
              glm::dot(glm::dvec3(r.frame.gbuffer.position[i]) + r.frame.gbuffer.origin - glm::dvec3(light.position),
                       glm::dvec3(light.normal)) <= 0.0;
  EXPECT_LE(statistic(r.frame, "pixels outside maps"), double(behind) + 0.01 * double(e.visibility.pixelsCounted));
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
  std::string t = info.param.technique;
  for (auto& ch : t)
    if (ch == '-') ch = '_';
  return sceneTestName(info.param.scene) + "_" + t;
}

// Measured (2026-12-01, llvmpipe): mvr agreement >= 0.999 and RMSE <= 0.011 except the thin
// pole at 3 degrees (0.045, in the edge band) and the cube (0.9964: samples grazing its front
// face, whose own depth the receiver-plane bias cannot resolve edge-on); vwss and reproject
// agreement >= 0.996.
INSTANTIATE_TEST_SUITE_P(Scenes, MultiViewVsRaytrace,
                         ::testing::Values(Case{"scenes/hard/01-cube-on-plane.json", "mvr", 0.995, 0.01},
                                           Case{"scenes/hard/04-open-quad.json", "mvr", 0.999, 0.015},
                                           Case{"scenes/hard/15-two-plates.json", "mvr", 0.999, 0.02},
                                           Case{"scenes/hard/20-light-behind-camera.json", "mvr", 0.999, 0.015},
                                           Case{"scenes/hard/23-analytic-square.json", "mvr", 0.999, 0.01},
                                           Case{"scenes/hard/23-analytic-disk.json", "mvr", 0.999, 0.01},
                                           Case{"scenes/hard/03-thin-pole-low-light.json", "mvr", 0.999, 0.06},
                                           Case{"scenes/stained-glass.json", "mvr", 0.998, 0.01},
                                           Case{"scenes/stained-glass.json", "vwss", 0.995, 0.02},
                                           Case{"scenes/hard/23-analytic-square.json", "vwss", 0.999, 0.01},
                                           Case{"scenes/hard/20-light-behind-camera.json", "vwss", 0.995, 0.02},
                                           Case{"scenes/hard/23-analytic-disk.json", "reproject", 0.999, 0.01},
                                           Case{"scenes/hard/22-points-behind-light.json", "mvr", 0.999, 0.015},
                                           Case{"scenes/hard/22-points-behind-light.json", "vwss", 0.998, 0.025},
                                           Case{"scenes/hard/22-points-behind-light.json", "vwss-unbuffered", 0.998,
                                                0.025}),
                         caseName);

// The VWSS paper's MVR is the accurate multi-view reference: its error falls as the maps grow.
TEST(MultiView, MvrConvergesAsMapsGrow) {
  Scene scene = loadScene(scenePath("scenes/stained-glass.json"));
  double previous = 1.0;
  for (int size : {128, 256, 1024}) {
    Comparison r = renderAndCompare(scene, "mvr", settings(128, 16), params({"map=" + std::to_string(size)}));
    RecordProperty("rmse_map" + std::to_string(size), std::to_string(r.errors.visibility.rmse));
    EXPECT_LT(r.errors.visibility.rmse, previous) << "map " << size;
    previous = r.errors.visibility.rmse;
  }
  EXPECT_LE(previous, 0.006);
}

// One instanced draw and one draw per map rasterise the same depths.
TEST(MultiView, LayeredDrawEqualsOneDrawPerMap) {
  Scene scene = defaultScene();
  Renderer renderer(context(), scene, settings(128, 16));
  auto a = makeTechnique("mvr", params({"map=512"}));
  auto b = makeTechnique("mvr-layered", params({"map=512"}));
  FrameResult fa = renderer.render(*a), fb = renderer.render(*b);
  EXPECT_LE(maxPerSampleDifference(fa, fb), 1e-6);
  EXPECT_EQ(statistic(fb, "draws"), 1.0);
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// Serial (k = 1), partially parallel (k = 8), fully parallel (k = 0) and unbuffered splats z-buffer
// the same points with integer atomics: the maps, hence the results, are identical. The graphics
// pipeline's depth test sees the same points.
TEST(MultiView, VwssPointRenderingVariantsAgree) {
  Scene scene = loadScene(scenePath("scenes/hard/15-two-plates.json"));
  Renderer renderer(context(), scene, settings(128, 16));
  auto base = makeTechnique("vwss", params({"map=512", "k=8"}));
  FrameResult ref = renderer.render(*base);
  EXPECT_GT(statistic(ref, "points"), 1000.0);
  EXPECT_EQ(statistic(ref, "point passes"), 2.0);
  for (const char* k : {"k=1", "k=0"}) {
    auto t = makeTechnique("vwss", params({"map=512", k}));
    EXPECT_EQ(maxPerSampleDifference(renderer.render(*t), ref), 0.0) << k;
  }
  auto unbuffered = makeTechnique("vwss-unbuffered", params({"map=512"}));
  EXPECT_EQ(maxPerSampleDifference(renderer.render(*unbuffered), ref), 0.0) << "unbuffered";
  auto graphics = makeTechnique("vwss-graphics", params({"map=512"}));
  FrameResult g = renderer.render(*graphics);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < g.lights[0].perSample.size(); ++i)
    differ += std::abs(g.lights[0].perSample[i] - ref.lights[0].perSample[i]) > 1e-6f;
  EXPECT_LE(double(differ), 1e-3 * double(g.lights[0].perSample.size())) << "graphics-pipeline points";
  // Keeping back faces (VWSS 3.1's option) adds the plates' undersides (the floor, most of the
  // points, has none); culling keeps the faces towards the light (the floor is among them).
  auto both = makeTechnique("vwss", params({"map=512", "backfaces=1"}));
  auto culled = makeTechnique("vwss", params({"map=512", "backfaces=0"}));
  FrameResult b = renderer.render(*both), cu = renderer.render(*culled);
  EXPECT_GT(statistic(b, "points"), 1.02 * statistic(cu, "points"));
  EXPECT_EQ(statistic(b, "back faces kept"), 1.0);
  EXPECT_EQ(statistic(cu, "back faces kept"), 0.0);
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// Hard case 32 (scenes/hard/32-large-light-near-box.json): a 3 x 3 light 0.01 above a box makes
// eq. 3 ask for more points than one storage block holds (GL_MAX_SHADER_STORAGE_BLOCK_SIZE,
// 128 MiB on llvmpipe and zink: 11.2 M points). vwss cuts its central view into bands that fit;
// the atomicMax maps do not depend on how the points were split, so a run split by
// --param pass-points equals the unsplit one. Back faces kept (backfaces=1): the light reaches
// 1 unit past the box on each side, so its corner samples see the box's sides, which face away
// from the central view (culled: visibility RMSE 0.24 against mvr's 0.015 at map 128; kept:
// 0.023, measured); the bound is mvr's RMSE + 0.01.
TEST(MultiView, VwssSplitsPointsIntoBands) {
  Scene scene = loadScene(scenePath("scenes/hard/32-large-light-near-box.json"));
  const RenderSettings s = settings(128, 16);
  Comparison one = renderAndCompare(scene, "vwss", s, params({"map=128", "backfaces=1"}));
  Comparison split = renderAndCompare(scene, "vwss", s, params({"map=128", "backfaces=1", "pass-points=1000000"}));
  EXPECT_EQ(statistic(one.frame, "point bands"), 1.0);
  EXPECT_GE(statistic(split.frame, "point bands"), 6.0);  // > 5.4 M points, at most 1 M a band
  EXPECT_EQ(statistic(split.frame, "points"), statistic(one.frame, "points"));
  EXPECT_LE(maxPerSampleDifference(split.frame, one.frame), 1e-6);
  const double mvr128 = renderAndCompare(scene, "mvr", s, params({"map=128"})).errors.visibility.rmse;
  EXPECT_LE(split.errors.visibility.rmse, mvr128 + 0.01);
}

// The GL's own limit, no hook: at map 256 eq. 3 gives a 7290^2 view and over 22.8 M points
// (273 MiB); before the split this was "a storage buffer of ... MiB exceeds ...".
TEST(MultiView, VwssSplitsPointsThatExceedOneStorageBlock) {
  Scene scene = loadScene(scenePath("scenes/hard/32-large-light-near-box.json"));
  const RenderSettings s = settings(128, 16);
  // (eq. 3 asks for a 7290^2 view here: past the default max-view, which would keep it in one block)
  Comparison big = renderAndCompare(scene, "vwss", s, params({"map=256", "backfaces=1", "max-view=16384"}));
  EXPECT_GT(12.0 * statistic(big.frame, "points"), double(gl::limits().maxStorageBlockSize));
  EXPECT_GE(statistic(big.frame, "point bands"), 2.0);
  const double mvr256 = renderAndCompare(scene, "mvr", s, params({"map=256"})).errors.visibility.rmse;
  RecordProperty("rmse_vwss_256", std::to_string(big.errors.visibility.rmse));
  RecordProperty("rmse_mvr_256", std::to_string(mvr256));
  EXPECT_LE(big.errors.visibility.rmse, mvr256 + 0.01);
}

// Hard case 39: an 8 x 8 light 0.35 above a floor. Eq. 3 asks for a 28225^2 point view (the GL's
// 16384^2 took 66 s a frame at 128 px); max-view stops it at 4096^2 (3.4 s), says so in the
// statistics, and the error stays mvr's (measured: vwss 0.0447 at 4096, 8192 and 16384 alike).
TEST(HardCase39, VwssViewIsBounded) {
  Scene scene = loadScene(scenePath("scenes/hard/39-large-light-near-floor.json"));
  const RenderSettings s = settings(128, 16);
  const Comparison vwss = renderAndCompare(scene, "vwss", s);
  EXPECT_EQ(statistic(vwss.frame, "source resolution"), 4096.0);
  EXPECT_EQ(statistic(vwss.frame, "source resolution capped"), 1.0);
  const double mvr = renderAndCompare(scene, "mvr", s).errors.visibility.rmse;
  std::printf("vwss %.4f, mvr %.4f visibility RMSE\n", vwss.errors.visibility.rmse, mvr);
  EXPECT_LE(vwss.errors.visibility.rmse, mvr + 0.01);
}

// Hard case 40: a rect light facing away from everything. It lights nothing, but its visibility
// buffer (eq. 2) is the cube's shadow, which no map holds: every map technique returned `none`'s
// visibility (RMSE 0.105, max 1.0 at 64 px) and reported no unshadowed pixel. Pixels behind a
// one-sided light now count as left unshadowed, so the report says so for every one of them.
TEST(HardCase40, MapTechniquesReportWhatALightFacingAwayLeavesUnshadowed) {
  const Scene scene = loadScene(scenePath("scenes/hard/40-light-facing-away.json"));
  for (const TechniqueInfo& t : techniqueTable()) {
    if (t.family != TechniqueFamily::SingleMap && t.family != TechniqueFamily::MultiView) continue;
    if (t.name.find("-") != std::string::npos && t.name != "msm-soft") continue;  // one of each base
    const Comparison r = renderAndCompare(scene, t.name, settings(64, 16));
    const std::int64_t surface = r.errors.visibility.pixelsCounted;
    EXPECT_GT(r.errors.visibility.rmse, 0.05) << t.name << ": the cube's shadow in eq. 2 is missed";
    EXPECT_EQ(r.errors.unshadowedPixels, surface) << t.name << ": every pixel is behind the light";
  }
}

// Hard case 35: a light that a closed opaque mesh separates from everything the camera sees (the
// camera in a closed box lit from outside; a light in a closed box seen from outside) lights no
// pixel. Before: the single-map techniques lit the box's inner walls (vssm visibility RMSE 0.47,
// max 1.0; pcss 0.41; msm-soft, evsm 0.41 at 64 px), vwss and reproject 0.22, all with status
// ok; they now cull the light (pipeline/enclosure.h) and equal the ray tracer.
TEST(HardCase35, MapTechniquesCullALightAClosedMeshSeparatesFromTheCamera) {
  const std::string culled = "lights culled (a closed mesh between them and the camera)";
  for (const char* file : {"scenes/hard/35-camera-in-closed-box.json", "scenes/hard/28-rect-inside-box.json"}) {
    const Scene scene = loadScene(scenePath(file));
    for (const char* name : {"pcss", "vssm", "msm", "msm-soft", "evsm", "vwss", "reproject"}) {
      const Comparison r = renderAndCompare(scene, name, settings(64, 16));
      EXPECT_EQ(statistic(r.frame, culled), 1.0) << file << " " << name;
      EXPECT_LE(r.errors.visibility.maxAbs, 1e-6) << file << " " << name;
    }
  }
}

// What the culling may not do: cull a light whose samples share a cell with what the camera
// sees. The camera 0.03 outside a closed box's wall with its near plane (0.05) inside the box
// sees the box's inside, where a light inside it shines; the camera 0.5 outside sees the wall's
// outside only. A light straddling a wall is named, not culled.
TEST(Enclosure, SeparatesOnlyWhatEveryPathCrosses) {
  const std::string box = scenePath("scenes/hard/35-camera-in-closed-box.json");
  const auto classify = [](const Scene& scene, int samples) {
    Enclosures e(scene, nearPlaneReach(scene.camera, 1.0));
    SamplingParams sp;
    sp.count = samples;
    const LightSampleSet set = makeLightSamples(scene, scene.lights[0], sp, 0.0f);
    return e.classify(0, scene.lights[0], set);
  };
  EXPECT_EQ(classify(loadScene(box), 16).separatedBy, "room");
  const std::vector<std::string> lightInside = {"lights.0.position=[0, 2, 0]", "camera.target=[2, 0.6, 0]"};
  auto nearInside = lightInside, farOutside = lightInside;
  nearInside.push_back("camera.position=[-2.03, 0.6, 0]");
  farOutside.push_back("camera.position=[-2.5, 0.6, 0]");
  EXPECT_EQ(classify(loadScene(box, nearInside), 16).separatedBy, "");
  EXPECT_EQ(classify(loadScene(box, farOutside), 16).separatedBy, "room");
  // Rendered, the near-plane case is lit where a culled light would leave it dark.
  const Scene seen = loadScene(box, nearInside);
  const Comparison r = renderAndCompare(seen, "pcss", settings(64, 16));
  EXPECT_EQ(statistic(r.frame, "lights culled (a closed mesh between them and the camera)"), 0.0);
  EXPECT_GT(r.reference.lights[0].visibility.data[32 * 64 * 3 + 32 * 3], 0.1f) << "the box's inside is lit";
  // The light straddling the cube's face: named, with its samples inside the cube counted.
  const LightEnclosure straddled = classify(loadScene(scenePath("scenes/hard/28-rect-partly-inside.json")), 16);
  EXPECT_EQ(straddled.separatedBy, "");
  EXPECT_NE(straddled.straddled, "");
  EXPECT_GT(straddled.samplesInOtherCells, 0u);
  EXPECT_LT(straddled.samplesInOtherCells, 16u);
}

// Never silent: a point-generation pass that yields no point while
// occluders fill the central view is an error naming vwss, not an unshadowed image. Provoked
// with a fragment shader that stores nothing (what Mesa 22.3's zink did to the real one).
TEST(MultiView, VwssWithoutPointsIsAnError) {
  char dir[] = "/tmp/penumbra-shaders-XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  std::ofstream(std::string(dir) + "/vwss_points.frag") << "#include \"shadow_map_points.glsl\"\nvoid main() {}\n";
  Scene scene = loadScene(scenePath("scenes/hard/15-two-plates.json"));
  Renderer renderer(context(), scene, settings(64, 4));
  auto vwss = makeTechnique("vwss", params({"map=128"}));
  setenv("PENUMBRA_SHADER_DIR", shaderSearchPath(dir).c_str(), 1);
  try {
    renderer.render(*vwss);
    ADD_FAILURE() << "no error for a pass without points";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vwss: the point-generation pass produced no point"), std::string::npos)
        << e.what();
  }
  unsetenv("PENUMBRA_SHADER_DIR");
  std::filesystem::remove_all(dir);
  gl::Context::takeErrorCount();
}

// Never silent: a depth-map pass that draws no fragment while occluders
// cover its view is an error naming the technique (mvr's maps, the single view of pcss and
// vssm, reproject's central map). Provoked with a depth shader that discards every fragment.
TEST(MultiView, DepthPassWithoutFragmentsIsAnError) {
  char dir[] = "/tmp/penumbra-shaders-XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  std::ofstream(std::string(dir) + "/depth_only.frag", std::ios::trunc) << "void main() { discard; }\n";
  Scene scene = loadScene(scenePath("scenes/hard/15-two-plates.json"));
  Renderer renderer(context(), scene, settings(64, 4));
  setenv("PENUMBRA_SHADER_DIR", shaderSearchPath(dir).c_str(), 1);
  for (const char* name : {"mvr", "mvr-layered", "pcss", "vssm", "reproject"}) {
    auto technique = makeTechnique(name, params({"map=128"}));
    try {
      renderer.render(*technique);
      ADD_FAILURE() << name << ": no error for a depth pass without fragments";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(std::string(name) + ": the ", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find("pass drew no fragment although occluder triangles cover"),
                std::string::npos)
          << e.what();
    }
  }
  unsetenv("PENUMBRA_SHADER_DIR");
  std::filesystem::remove_all(dir);
  gl::Context::takeErrorCount();
}

// Unsynchronised reprojection: the last writer wins instead of the nearest, so a texel whose
// points come from several depths may keep a farther one. On the default scene few decisions
// change; the error against the reference is recorded next to the synchronised one's.
TEST(MultiView, UnsynchronisedReprojectionStaysCloseToSynchronised) {
  Scene scene = defaultScene();
  Renderer renderer(context(), scene, settings(128, 16));
  auto sync = makeTechnique("reproject", params({"map=512"}));
  auto unsync = makeTechnique("reproject-unsync", params({"map=512"}));
  FrameResult a = renderer.render(*sync), u = renderer.render(*unsync);
  std::size_t differ = 0, n = a.lights[0].perSample.size();
  ASSERT_EQ(n, u.lights[0].perSample.size());
  for (std::size_t i = 0; i < n; ++i) differ += std::abs(a.lights[0].perSample[i] - u.lights[0].perSample[i]) > 0.1f;
  RecordProperty("differing_fraction", std::to_string(double(differ) / double(n)));
  EXPECT_LE(double(differ), 0.05 * double(n));
  EXPECT_GT(statistic(u, "point passes"), 0.0);
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// Hard case 15 (two plates): the lower plate is hidden from the light centre by the upper one but
// seen from the light's corners. Reprojecting the central z-buffer loses it (light leaks, VWSS
// Figure 4 left); VWSS keeps every layer and matches MVR.
TEST(MultiView, VwssFixesTheLeaksOfFragmentReprojection) {
  Scene scene = loadScene(scenePath("scenes/hard/15-two-plates.json"));
  double mvr = renderAndCompare(scene, "mvr", settings(128, 16)).errors.visibility.rmse;
  double vwss = renderAndCompare(scene, "vwss", settings(128, 16)).errors.visibility.rmse;
  double reproject = renderAndCompare(scene, "reproject", settings(128, 16)).errors.visibility.rmse;
  RecordProperty("rmse_mvr", std::to_string(mvr));
  RecordProperty("rmse_vwss", std::to_string(vwss));
  RecordProperty("rmse_reproject", std::to_string(reproject));
  EXPECT_LE(vwss, 1.2 * mvr + 0.002);
  EXPECT_GE(reproject, 3.0 * vwss);
}

// Interleaved sampling: each set of samples has its own maps (layer = set * N + k).
// Hard case 29: vwss culls back faces (as seen from its central eye) only when that cannot drop
// a nearest occluder. A light below the single-sided floor, inside a closed box or inside the
// cube needs them (the pipeline's culling of lights a closed mesh separates from the camera off):
// culled, the floor or the box vanish from the maps (culling was once the
// default: RMSE 0.28 / 0.89 / 0.96 at 128 px); kept, vwss is as close to the reference as mvr
// (below the floor, inside the cube) or several times closer than culled (inside the box, where
// the walls seen at grazing angles leave holes in the splatted maps). A cube lit from above keeps
// culling, with the same result as forcing it.
TEST(MultiView, VwssKeepsBackFacesWhereTheLightNeedsThem) {
  struct Case {
    const char* scene;
    double overMvr;      // auto's RMSE <= mvr's + this, or < 0: no bound against mvr
    double underCulled;  // auto's RMSE <= this x backfaces=0's
  };
  for (Case c :
       {Case{"scenes/hard/29-light-below-floor.json", 0.005, 0.3}, Case{"scenes/hard/27-point-inside.json", 0.005, 0.6},
        Case{"scenes/hard/28-rect-inside-box.json", -1.0, 0.4}}) {
    Scene scene = loadScene(scenePath(c.scene));
    RenderSettings s = settings(96, 16);
    s.cullSeparatedLights = false;  // the technique's own answer for a light inside a closed mesh
    Comparison autoRun = renderAndCompare(scene, "vwss", s, params({"map=512"}));
    Comparison culled = renderAndCompare(scene, "vwss", s, params({"map=512", "backfaces=0"}));
    const double a = autoRun.errors.visibility.rmse, k = culled.errors.visibility.rmse;
    RecordProperty(std::string("rmse_auto_") + sceneTestName(c.scene), std::to_string(a));
    RecordProperty(std::string("rmse_culled_") + sceneTestName(c.scene), std::to_string(k));
    EXPECT_EQ(statistic(autoRun.frame, "back faces kept"), 1.0) << c.scene;
    EXPECT_LE(a, c.underCulled * k) << c.scene;
    if (c.overMvr >= 0.0) {
      const double mvr = renderAndCompare(scene, "mvr", s, params({"map=512"})).errors.visibility.rmse;
      EXPECT_LE(a, mvr + c.overMvr) << c.scene;
    }
  }
  Scene cube = loadScene(scenePath("scenes/hard/01-cube-on-plane.json"));
  Renderer renderer(context(), cube, settings(96, 16));
  auto autoVwss = makeTechnique("vwss", params({"map=512"}));
  auto culledVwss = makeTechnique("vwss", params({"map=512", "backfaces=0"}));
  FrameResult a = renderer.render(*autoVwss), k = renderer.render(*culledVwss);
  EXPECT_EQ(statistic(a, "back faces kept"), 0.0);
  EXPECT_EQ(maxPerSampleDifference(a, k), 0.0);
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

TEST(MultiView, InterleavedSetsUseTheirOwnMaps) {
  RenderSettings s = settings(128, 16);
  s.sampling.pattern = PixelPattern::Interleaved;
  s.sampling.interleaveK = 2;
  s.interleaveFilter = false;
  Comparison r =
      renderAndCompare(loadScene(scenePath("scenes/hard/23-analytic-square.json")), "mvr", s, params({"map=512"}));
  EXPECT_EQ(statistic(r.frame, "maps"), 64.0);
  EXPECT_GE(r.errors.sampleAgreement, 0.999);
}

// Sphere and point lights have no normal: the maps look from the light towards the receivers.
TEST(MultiView, SphereLightLooksAtTheReceivers) {
  Scene scene =
      loadScene(scenePath("scenes/hard/01-cube-on-plane.json"), {"lights.0.type=sphere", "lights.0.radius=0.3"});
  Comparison r = renderAndCompare(scene, "mvr", settings(128, 16));
  EXPECT_GE(r.errors.sampleAgreement, 0.995);
  EXPECT_LE(r.errors.visibility.rmse, 0.02);
  EXPECT_EQ(statistic(r.frame, "pixels outside maps"), 0.0);
}

// Semi-opaque occluders: per-map lists of the semi-opaque surfaces on each texel (depth and
// opacity), K sized to the scene. The panes of scenes/semi-opaque.json overlap (up to 6
// surfaces on a texel); the product of the entries in front of each receiver gives visibility
// RMSE 0.013-0.015 against the reference with 512^2 maps (0.0095-0.0115 with 1024^2; measured
// 2026-12-01; 0.14 when the panes were drawn as opaque occluders).
TEST(MultiView, SemiOpaqueOccludersMultiplyTransmittance) {
  Scene scene = loadScene(scenePath("scenes/semi-opaque.json"));
  for (const char* t : {"mvr", "vwss", "reproject"}) {
    Comparison r = renderAndCompare(scene, t, settings(128, 16), params({"map=512"}));
    EXPECT_GT(statistic(r.frame, "semi-opaque triangles"), 0.0) << t;
    EXPECT_GT(statistic(r.frame, "semi-opaque map bytes"), 0.0) << t;
    RecordProperty(std::string("visibility_rmse_") + t, std::to_string(r.errors.visibility.rmse));
    EXPECT_LE(r.errors.visibility.rmse, 0.02) << t;
    EXPECT_GE(statistic(r.frame, "semi-opaque entries per texel"), 4.0) << t;
  }
  // The first frame measured K (and was redone with it); the next needs no rerun.
  Renderer renderer(context(), scene, settings(64, 4));
  auto mvr = makeTechnique("mvr", params({"map=256"}));
  renderer.render(*mvr);
  EXPECT_EQ(statistic(renderer.render(*mvr), "semi-opaque reruns"), 0.0);
  // A scene without semi-opaque surfaces allocates nothing for them.
  Comparison plain =
      renderAndCompare(loadScene(scenePath("scenes/hard/01-cube-on-plane.json")), "mvr", settings(64, 4));
  EXPECT_EQ(statistic(plain.frame, "semi-opaque map bytes"), 0.0);
}

// Hard case 22: points behind a sample's camera, on its plane (w = +-0), NaN and Inf points and
// points outside the frustum leave the maps unchanged; a valid point lands on its texel with its
// reversed depth.
TEST(MultiView, SplatIgnoresPointsBehindTheCameraAndNonFinitePoints) {
  context();
  shadow_map::MapFrame f;
  f.axis = {0, -1, 0};
  f.right = {1, 0, 0};
  f.up = glm::cross(f.right, f.axis);
  f.tanHalf = 1.0f;
  f.zNear = 0.01f;
  f.size = 8;
  f.layers = 2;
  std::vector<glm::vec3> samples = {{0, 4, 0}, {0.5f, 4, 0}};
  gl::Buffer sampleBuffer = lightSampleBuffer(samples, int(samples.size()));
  sampleBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_LIGHT_SAMPLES);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::vector<glm::vec3> pts = {
      {0.1f, 2.0f, 0.1f},          // valid for both samples
      {0.0f, 5.0f, 0.0f},          // behind both cameras (w < 0)
      {0.0f, 4.0f, 0.0f},          // on sample 0's plane (w = 0)
      {0.3f, -0.0f + 4.0f, 0.2f},  // on the plane again
      {0.0f, 3.995f, 0.0f},        // in front of the camera but nearer than the near plane
      {nan, 2.0f, 0.0f},           // NaN
      {0.0f, -inf, 0.0f},          // Inf
      {100.0f, 2.0f, 0.0f},        // outside the frustum
  };
  std::vector<float> data(4, 0.0f);
  std::uint32_t count = std::uint32_t(pts.size());
  std::memcpy(&data[0], &count, sizeof(count));
  for (auto& p : pts) data.insert(data.end(), {p.x, p.y, p.z});
  gl::Buffer pointBuffer(data);
  pointBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_POINTS);
  auto maps = gl::Texture::make2DArray(GL_R32UI, f.size, f.size, f.layers);
  maps.clear(glm::vec4(0.0f));
  gl::Program prog({"shadow_map_reproject.comp"});
  shadow_map::setMapUniforms(prog, f);
  prog.set("pointCapacity", unsigned(pts.size()));
  shadow_map::splatMaps(prog, maps, pts.size(), f.layers, {});
  std::vector<std::uint32_t> texels = maps.readUint();
  for (int l = 0; l < f.layers; ++l) {
    glm::vec3 r = pts[0] - glm::vec3(samples[std::size_t(l)]);
    float d = glm::dot(r, f.axis);
    float x = glm::dot(r, f.right) / (d * f.tanHalf), y = glm::dot(r, f.up) / (d * f.tanHalf);
    int tx = int(std::floor((x * 0.5f + 0.5f) * f.size)), ty = int(std::floor((0.5f - 0.5f * y) * f.size));
    for (int j = 0; j < f.size; ++j)
      for (int i = 0; i < f.size; ++i) {
        std::uint32_t v = texels[(std::size_t(l) * f.size + j) * f.size + i];
        if (i == tx && j == ty) {
          float z;
          std::memcpy(&z, &v, sizeof(z));
          EXPECT_NEAR(z, f.zNear / d, 1e-6f * f.zNear / d) << "layer " << l;
        } else {
          EXPECT_EQ(v, 0u) << "layer " << l << " texel " << i << "," << j;
        }
      }
  }
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

}  // namespace
}  // namespace penumbra::test
