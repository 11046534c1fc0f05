// Time that measures the technique: the harness's readbacks apart from the
// technique's stages, shadow-map frusta fitted on the GPU (no G-buffer readback), single-view
// frusta fitted to the light (not its samples), and per-stage pipeline statistics.
#include <algorithm>
#include <cmath>

#include "render_test_util.h"
#include "gl/statistics.h"
#include "sampling/light_samples.h"
#include "techniques/common/shadow_map/maps.h"

namespace penumbra::test {
namespace {

const StageTime* findStage(const FrameResult& f, const std::string& name) {
  for (auto& s : f.timer.stages())
    if (s.stage == name) return &s;
  return nullptr;
}

// The shadow-map techniques render without the CPU G-buffer; readbacks (and raytrace's upload)
// are harness stages, outside the frame's total; raytrace still reads the G-buffer it traces.
TEST(Timing, HarnessStagesApartAndMapsNeedNoGBufferReadback) {
  Scene scene = defaultScene();
  RenderSettings s = settings(64, 8);
  s.gbufferResults = false;
  Renderer renderer(context(), scene, s);
  for (const char* name : {"pcss", "vssm", "mvr", "vwss", "reproject"}) {
    auto t = makeTechnique(name);
    FrameResult f = renderer.render(*t);
    EXPECT_EQ(findStage(f, "gbuffer readback"), nullptr) << name;
    EXPECT_TRUE(f.gbuffer.valid.empty()) << name;
    const StageTime* readback = findStage(f, "readback");
    ASSERT_NE(readback, nullptr) << name;
    EXPECT_EQ(readback->kind, StageKind::Harness) << name;
    double technique = 0.0, harness = 0.0;
    for (auto& st : f.timer.stages()) (st.kind == StageKind::Harness ? harness : technique) += st.ms;
    EXPECT_DOUBLE_EQ(f.timer.total(), technique) << name;
    EXPECT_DOUBLE_EQ(f.timer.harnessTotal(), harness) << name;
    EXPECT_GT(harness, 0.0) << name;
  }
  auto rt = makeTechnique("raytrace");
  FrameResult f = renderer.render(*rt);
  ASSERT_NE(findStage(f, "gbuffer readback"), nullptr);
  EXPECT_EQ(findStage(f, "gbuffer readback")->kind, StageKind::Harness);
  ASSERT_NE(findStage(f, "upload"), nullptr);
  EXPECT_EQ(findStage(f, "upload")->kind, StageKind::Harness);
  EXPECT_EQ(findStage(f, "trace")->kind, StageKind::Technique);
  EXPECT_FALSE(f.gbuffer.valid.empty());
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// Pixels whose receiver plane has the whole light above it (every sample above the horizon):
// there a single-view technique's visibility is its shadow factor alone (elsewhere it is scaled
// by the fraction of samples above the horizon, src/techniques/common/shadow_map/shaders/pcss_common.glsl
// horizonLuminance, which depends on the samples as the reference's integral does).
std::vector<std::uint8_t> wholeLightAbove(const FrameResult& f, const Light& light, const glm::dvec3& origin) {
  std::vector<std::uint8_t> out(f.gbuffer.valid.size(), 0);
  const glm::dvec3 c = glm::dvec3(light.position) - origin;  // camera-relative, as the G-buffer
  const double margin = 1e-3;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!f.gbuffer.valid[i]) continue;
    const glm::dvec3 p(f.gbuffer.position[i]), n(f.gbuffer.normal[i]);
    double lowest = glm::dot(n, c - p);
    if (light.shape == LightShape::Sphere || light.shape == LightShape::Disk) {
      lowest -= light.size.x;  // a ball's (and, more than enough, a disk's) radius
    } else if (light.shape == LightShape::Rect) {
      for (double u : {-0.5, 0.5})
        for (double v : {-0.5, 0.5})
          lowest = std::min(lowest, glm::dot(n, c + u * double(light.size.x) * glm::dvec3(light.tangent) +
                                                    v * double(light.size.y) * glm::dvec3(light.bitangent()) - p));
    }
    out[i] = lowest > margin;
  }
  return out;
}

// pcss and vssm use no light samples for their shadow: their map's frustum holds the whole
// light, so --samples and --seed change neither the map nor the shadow factor (the frustum used
// to be fitted to the samples: half-angle 59.35 deg at 16, 59.40 at 64, which moved pcss's bias
// from -4.8e-3 to +4.3e-3).
TEST(Timing, SingleViewMapsIgnoreSamplesAndSeed) {
  for (const char* path : {"", "scenes/hard/23-analytic-disk.json", "scenes/hard/28-sphere-touching.json"}) {
    Scene scene = *path ? loadScene(scenePath(path)) : defaultScene();
    // Untextured: a textured light's mean luminance over the samples is theirs to change.
    scene.lights[0].emissionFrames.clear();
    const glm::dvec3 origin = glm::dvec3(scene.camera.position);
    for (const char* name : {"pcss", "vssm"}) {
      auto render = [&](int samples, std::uint32_t seed) {
        RenderSettings s = settings(64, samples);
        s.sampling.seed = seed;
        Renderer renderer(context(), scene, s);
        auto t = makeTechnique(name);
        return renderer.render(*t);
      };
      const FrameResult a = render(16, 1), b = render(64, 1), c = render(16, 7);
      const std::string at = std::string(name) + " " + (*path ? path : "default");
      const std::vector<std::uint8_t> above = wholeLightAbove(a, scene.lights[0], origin);
      std::size_t compared = 0, shadowed = 0;
      double diff = 0.0;
      for (const FrameResult* other : {&b, &c})
        for (std::size_t i = 0; i < above.size(); ++i) {
          if (!above[i]) continue;
          for (int ch = 0; ch < 3; ++ch) {
            const float va = a.lights[0].visibility.data[i * 3 + std::size_t(ch)];
            diff = std::max(diff, double(std::abs(va - other->lights[0].visibility.data[i * 3 + std::size_t(ch)])));
            shadowed += ch == 0 && va < 0.5f;
          }
          ++compared;
        }
      RecordProperty("max_diff_" + std::string(name), std::to_string(diff));
      EXPECT_GT(compared, 200u) << at;
      EXPECT_GT(shadowed, 0u) << at << ": some compared pixels are in shadow";
      EXPECT_LE(diff, 1e-5) << at;
      EXPECT_NEAR(statistic(a, "frustum half-angle deg"), statistic(b, "frustum half-angle deg"), 1e-5) << at;
      EXPECT_NEAR(statistic(a, "frustum half-angle deg"), statistic(c, "frustum half-angle deg"), 1e-5) << at;
      EXPECT_EQ(statistic(a, "search near"), statistic(b, "search near")) << at;
      EXPECT_EQ(statistic(a, "pixels outside maps"), statistic(b, "pixels outside maps")) << at;
    }
  }
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// The GPU reductions of shadow_map_fit.comp against the same sums on the CPU G-buffer: the
// receivers' centroid (a sphere light's axis), the widest receiver and the pixels outside.
TEST(Timing, GpuFrustumFitMatchesTheCpu) {
  context();
  for (const char* path : {"", "scenes/hard/28-sphere-touching.json"}) {
    Scene scene = *path ? loadScene(scenePath(path)) : defaultScene();
    scene.makeCameraRelative();
    GpuScene gpu(scene, 80, 64);
    gpu.renderGBuffer();
    const CpuGBuffer g = gpu.readGBuffer();
    const Light& light = scene.lights[0];
    SamplingParams sp;
    sp.count = 16;
    const LightSampleSet samples = makeLightSamples(scene, light, sp, 0.0f);
    for (double maxAngle : {80.0, 35.0}) {
      shadow_map::MapOptions o;
      o.maxHalfAngle = maxAngle;
      shadow_map::FrameFit fit;
      const shadow_map::MapFrame f = fit.compute(gpu, light, samples, o, shadow_map::MapReach::Samples);
      const std::string at = std::string(*path ? path : "default") + " max-angle " + std::to_string(maxAngle);
      if (light.shape == LightShape::Sphere) {
        glm::dvec3 sum(0.0);
        std::size_t n = 0;
        for (std::size_t i = 0; i < g.position.size(); ++i)
          if (g.valid[i]) sum += glm::dvec3(g.position[i]), ++n;
        ASSERT_GT(n, 0u);
        const glm::vec3 axis = glm::normalize(glm::vec3(sum / double(n)) - light.position);
        EXPECT_NEAR(glm::dot(axis, f.axis), 1.0, 1e-6) << at;
      }
      const float tanMax = std::tan(glm::radians(float(maxAngle)));
      float tanHalf = 0.0f;
      std::vector<std::uint8_t> mask(g.position.size(), 0);
      std::size_t outside = 0;
      for (std::size_t i = 0; i < g.position.size(); ++i) {
        if (!g.valid[i]) continue;
        const glm::vec3 r = g.position[i] - light.position;
        const float depth = glm::dot(r, f.axis) - f.sampleAxialMax;
        const float lateral = std::max(std::abs(glm::dot(r, f.right)), std::abs(glm::dot(r, f.up))) + f.sampleLateral;
        if (depth <= f.zNear || lateral > tanMax * depth)
          mask[i] = 1, ++outside;
        else
          tanHalf = std::max(tanHalf, lateral / depth);
      }
      ASSERT_GT(tanHalf, 0.0f) << at;
      EXPECT_NEAR(f.tanHalf, tanHalf * (1.0f + 4.0f / float(f.size)), 1e-6 * tanHalf) << at;
      EXPECT_EQ(f.outsidePixels, outside) << at;
      if (maxAngle < 40.0) {
        EXPECT_GT(outside, 0u) << at << ": the narrow frustum leaves receivers outside";
      }
      const std::vector<std::uint8_t> gpuMask = fit.outsideMask();
      if (outside == 0) {
        EXPECT_TRUE(gpuMask.empty()) << at;
      } else {
        EXPECT_EQ(gpuMask, mask) << at;
      }
    }
  }
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// Per stage, the GL's pipeline statistics where it has them (llvmpipe and zink do): the
// G-buffer draws the scene's triangles; vssm's tables are compute; mvr-layered's maps go through
// a geometry shader. Without them no stage claims counts (reports say "not counted").
TEST(Timing, PipelineStatisticsPerStage) {
  Scene scene = defaultScene();
  Renderer renderer(context(), scene, settings(64, 8));
  auto vssm = makeTechnique("vssm");
  auto layered = makeTechnique("mvr-layered");
  const FrameResult fv = renderer.render(*vssm), fm = renderer.render(*layered);
  if (!gl::PipelineStatistics::supported()) {
    for (const FrameResult* f : {&fv, &fm})
      for (auto& st : f->timer.stages()) EXPECT_FALSE(st.counted) << st.stage;
    return;
  }
  const StageTime* gbuffer = findStage(fv, "gbuffer");
  ASSERT_NE(gbuffer, nullptr);
  ASSERT_TRUE(gbuffer->counted);
  EXPECT_EQ(gbuffer->counts.primitivesSubmitted, scene.triangleCount());
  EXPECT_GT(gbuffer->counts.fragmentInvocations, 0u);
  EXPECT_EQ(gbuffer->counts.computeInvocations, 0u);
  const StageTime* sat = findStage(fv, "vssm sat");
  ASSERT_NE(sat, nullptr);
  EXPECT_GT(sat->counts.computeInvocations, 0u);
  const StageTime* maps = findStage(fm, "mvr-layered depth maps");
  ASSERT_NE(maps, nullptr);
  EXPECT_GT(maps->counts.geometryInvocations, 0u);
  EXPECT_GT(maps->counts.fragmentInvocations, 0u);
  // Switched off: nothing counted.
  RenderSettings off = settings(64, 8);
  off.pipelineStatistics = false;
  Renderer plain(context(), scene, off);
  const FrameResult uncounted = plain.render(*vssm);
  for (auto& st : uncounted.timer.stages()) EXPECT_FALSE(st.counted) << st.stage;
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

}  // namespace
}  // namespace penumbra::test
