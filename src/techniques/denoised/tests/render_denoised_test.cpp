// `raytrace-denoised`: 1-4 shadow rays per pixel, temporal accumulation and a
// penumbra-sized cross-bilateral filter, against the Embree reference with the same samples and
// the converged one, on a still scene over frames (the accumulation converges to the N samples'
// ratio) and with a moving occluder (flicker and lag). Tolerances are the measured values
// (llvmpipe, 128 px, 16 samples) with a margin.
#include <cmath>
#include <utility>

#include "render_test_util.h"

namespace penumbra::test {
namespace {

// The RMSE of each of `frames` successive frames of one technique object against the same-sample
// reference of the same renderer.
std::vector<double> errorsOverFrames(const Scene& scene, const std::vector<std::string>& params, int frames,
                                     const char* technique = "raytrace-denoised") {
  Renderer renderer(context(), scene, settings(128, 16));
  auto ref = makeTechnique("raytrace");
  const FrameResult reference = renderer.render(*ref);
  auto t = makeTechnique(technique, TechniqueParams(params));
  std::vector<double> errors;
  for (int f = 0; f < frames; ++f) errors.push_back(measureErrors(renderer.render(*t), reference).visibility.rmse);
  return errors;
}

}  // namespace

// On a still scene the history cycles through the pixel's N samples: after N / spp frames the
// accumulated ratio is the N samples' own, and only the (shrunk, at least 1 px) filter's blur
// remains. Frame 0 is the spp-sample estimate, filtered (measured: spp 1 0.0234 -> 0.0089 after
// 16 frames, spp 4 0.0207 -> 0.0127 after 4).
TEST(RaytraceDenoised, StillSceneConvergesToTheSameSamples) {
  const Scene scene = loadScene(scenePath("scenes/hard/23-analytic-square.json"));
  for (int spp : {1, 4}) {
    const std::vector<double> e = errorsOverFrames(scene, {"spp=" + std::to_string(spp)}, 16 / spp + 1);
    std::printf("spp %d: frame 0 %.4f, frame %d %.4f\n", spp, e.front(), 16 / spp, e.back());
    EXPECT_LT(e.back(), (spp == 1 ? 0.5 : 0.7) * e.front()) << spp;
    EXPECT_LE(e.front(), 0.03) << spp;
  }
  const std::vector<double> still = errorsOverFrames(scene, {"temporal=0"}, 4);
  EXPECT_NEAR(still.front(), still.back(), 0.02) << "without history each frame stands alone";
}

// The spinning fan under --frames (compare): temporal accumulation cuts the flicker of the
// frame-by-frame estimate by a third (the history is clamped to each frame's filtered value, so
// the blades' shadows do not smear), more rays per pixel lower it further; dcs changes exactly as
// the reference (measured at 96 px, 8 frames: spp 1 0.0257, without history 0.0384, spp 4 0.0178).
TEST(RaytraceDenoised, FlickerUnderMotion) {
  Scene fan = loadScene(scenePath("scenes/spinning-fan.json"));
  ASSERT_TRUE(fan.isAnimated());
  auto flicker = [&](const std::vector<std::string>& params, const char* technique = "raytrace-denoised") {
    CompareOptions o = compareOptions({technique});
    o.frames = 8, o.warmup = 0, o.progress = 0;
    o.params = params;
    CompareResult r = compareTechniques(context(), fan, settings(96, 16), o);
    for (auto& run : r.runs)
      if (run.technique == technique) return std::pair(run.flicker, run.meanFrameRmse);
    ADD_FAILURE() << "no run";
    return std::pair(-1.0, -1.0);
  };
  const auto [one, oneRmse] = flicker({"spp=1"});
  const auto [alone, aloneRmse] = flicker({"spp=1", "temporal=0"});
  const auto [four, fourRmse] = flicker({"spp=4"});
  const auto [ffx, ffxRmse] = flicker({"spp=1"}, "raytrace-ffx");
  std::printf("ffx: flicker %.4f (%.4f)\n", ffx, ffxRmse);
  RecordProperty("flicker_ffx_spp1", std::to_string(ffx));
  // The FidelityFX-style denoiser on the same rays flickers less than ours (its history clamped to
  // the neighbourhood's moments, not to the filtered value; measured 0.0229) at a higher mean
  // frame error (0.0475 against 0.0428).
  EXPECT_LT(ffx, 0.8 * alone);
  EXPECT_LE(ffxRmse, 0.055);
  std::printf("flicker (mean frame RMSE): spp 1 %.4f (%.4f), without history %.4f (%.4f), spp 4 %.4f (%.4f)\n", one,
              oneRmse, alone, aloneRmse, four, fourRmse);
  RecordProperty("flicker_spp1", std::to_string(one));
  RecordProperty("flicker_spp4", std::to_string(four));
  EXPECT_LT(one, 0.8 * alone);
  EXPECT_LT(four, one);
  EXPECT_LE(one, 0.035);
  EXPECT_LE(four, 0.025);
}

// The FidelityFX-style denoiser (raytrace-ffx) on the same rays as ours: on a still scene its
// history converges to the N samples' ratio as ours does; tiles with no variance (the lit floor
// around the plate) are not filtered. Measured (128 px, N = 16, spp 1, frame 0 -> frame 16):
// ffx 0.0283 -> 0.0088, ours 0.0234 -> 0.0089; 82% of the tiles uniform (not filtered).
TEST(RaytraceFfx, StillSceneConvergesOnTheSameRaysAsOurs) {
  const Scene scene = loadScene(scenePath("scenes/hard/23-analytic-square.json"));
  const std::vector<double> ffx = errorsOverFrames(scene, {"spp=1"}, 17, "raytrace-ffx");
  const std::vector<double> ours = errorsOverFrames(scene, {"spp=1"}, 17);
  std::printf("ffx: frame 0 %.4f, frame 16 %.4f; ours %.4f, %.4f\n", ffx.front(), ffx.back(), ours.front(),
              ours.back());
  RecordProperty("ffx_frame0_frame16", std::to_string(ffx.front()) + " " + std::to_string(ffx.back()));
  RecordProperty("ours_frame0_frame16", std::to_string(ours.front()) + " " + std::to_string(ours.back()));
  EXPECT_LT(ffx.back(), 0.5 * ffx.front());
  EXPECT_LE(ffx.front(), 0.035);
  EXPECT_LE(ffx.back(), 0.012);
  const Comparison one = renderAndCompare(scene, "raytrace-ffx", settings(128, 16));
  RecordProperty("uniform_tiles", std::to_string(statistic(one.frame, "uniform tiles")));
  EXPECT_GE(statistic(one.frame, "uniform tiles"), 0.3);
  EXPECT_EQ(statistic(one.frame, "ffx denoiser"), 1.0);
}

}  // namespace penumbra::test

namespace penumbra::test {

// Hard case 35: the camera inside a closed box, the light outside straddling a wall's plane.
// Everything in view is in shadow. raytrace-denoised traced each pixel's rotating sample even when
// it lay below the horizon, kept ratio 1 for such a pixel and lit the walls up to 0.26 (image
// RMSE 0.11 at 64 px); its rays now rotate over the samples above the horizon, and it equals the
// ray tracer.
TEST(HardCase35, DenoisedKeepsAClosedBoxDark) {
  const Scene scene = loadScene(scenePath("scenes/hard/35-camera-in-closed-box.json"));
  for (auto [technique, spp] :
       {std::pair{"raytrace-denoised", "1"}, std::pair{"raytrace-denoised", "4"}, std::pair{"raytrace-ffx", "1"}}) {
    const Comparison r = renderAndCompare(scene, technique, settings(64, 16), params({std::string("spp=") + spp}));
    std::printf("spp %s: visibility RMSE %.3g, max %.3g\n", spp, r.errors.visibility.rmse, r.errors.visibility.maxAbs);
    EXPECT_LE(r.errors.visibility.maxAbs, 1e-6) << technique << " spp " << spp;
    // The scene is dark for the reference too (and has surface in view), or this proves nothing.
    ASSERT_GT(r.errors.visibility.pixelsCounted, 64 * 64 / 2);
    double lit = 0.0;
    for (float v : r.reference.lights[0].visibility.data) lit = std::max(lit, double(v));
    EXPECT_EQ(lit, 0.0);
  }
}

}  // namespace penumbra::test
