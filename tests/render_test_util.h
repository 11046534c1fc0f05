// Helpers for rendering tests: render a scene with a technique and compare with the reference.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <initializer_list>
#include <filesystem>
#include <memory>
#include <string>

#include "core/error.h"
#include "gl/context.h"
#include "compare/compare.h"
#include "pipeline/renderer.h"
#include "scene/scene.h"
#include "techniques/registry.h"
#include "test_util.h"

namespace penumbra::test {

inline std::string scenePath(const std::string& rel) { return std::string(PENUMBRA_SOURCE_DIR) + "/" + rel; }

// A $PENUMBRA_SHADER_DIR that reads `first` before the source tree's shader folders (shaders/,
// src/shared/ and every shaders/ under src/): a test's replacement of one file, the others as
// built.
inline std::string shaderSearchPath(const std::string& first) {
  std::string path = first + ":" + scenePath("shaders") + ":" + scenePath("src/shared");
  for (const auto& e : std::filesystem::recursive_directory_iterator(scenePath("src")))
    if (e.is_directory() && e.path().filename() == "shaders") path += ":" + e.path().string();
  return path;
}

inline gl::Context& context() {
  static std::unique_ptr<gl::Context> c = gl::Context::create(gl::Backend::Egl);
  c->makeCurrent();  // another test may have made its own context current
  return *c;
}

inline RenderSettings settings(int size, int samples) {
  RenderSettings s;
  s.width = s.height = size;
  s.sampling.count = samples;
  return s;
}

// Compare options for `techniques` against the raytrace references of the table.
inline CompareOptions compareOptions(const std::vector<std::string>& techniques) {
  CompareOptions o;
  o.techniques = findTechniques(techniques);
  o.reference = findTechnique("raytrace");
  o.convergedReference = findTechnique("raytrace-converged");
  return o;
}

struct Comparison {
  FrameResult frame, reference;
  TechniqueErrors errors;
};

// Renders `technique` and `raytrace` (same samples) and measures the errors; fails the test on
// any GL error.
inline Comparison renderAndCompare(const Scene& scene, const std::string& technique, const RenderSettings& s,
                                   const TechniqueParams& params = {}) {
  Renderer renderer(context(), scene, s);
  auto tech = makeTechnique(technique, params);
  auto ref = makeTechnique("raytrace");
  Comparison c;
  c.frame = renderer.render(*tech, technique);
  c.reference = renderer.render(*ref, "raytrace");
  c.errors = measureErrors(c.frame, c.reference);
  EXPECT_EQ(gl::Context::takeErrorCount(), 0) << "GL errors while rendering " << technique;
  return c;
}

inline TechniqueParams params(const std::vector<std::string>& keyValues) { return TechniqueParams(keyValues); }

// raytrace-converged with at most `maxSamples` light (and BRDF) samples a pixel: tests that
// measure visibility against it need only its minimum (2048, the default here); tests of shading
// a cap that keeps them under their time budget (its 1e-3 target is reached where it can be).
inline std::unique_ptr<Technique> convergedReference(int maxSamples = 2048) {
  return makeTechnique("raytrace-converged", TechniqueParams({"reference-max-samples=" + std::to_string(maxSamples)}));
}

// A Technique::statistics() value of a frame (fails the test if absent).
inline double statistic(const FrameResult& f, const std::string& key) {
  if (auto v = findStatistic(f, key)) return *v;
  ADD_FAILURE() << "no statistic " << key;
  return 0.0;
}

// Fraction of surface pixels outside the edge band whose visibility decision differs.
inline double misclassifiedFraction(const TechniqueErrors& e) {
  return e.visibilityOutsideBand.pixelsCounted
             ? double(e.misclassifiedPixels) / double(e.visibilityOutsideBand.pixelsCounted)
             : 0.0;
}

// Light bleeding against vssm on a scene (the moment techniques, msm and evsm): `technique`'s RMSE against the
// same-sample reference at most `gate` and below `factor` x vssm's (printed and recorded).
struct BleedCase {
  const char* path;
  double gate;
};
inline void expectBleedsLessThanVssm(const char* technique, std::initializer_list<BleedCase> cases, double factor) {
  for (const BleedCase& c : cases) {
    Scene scene = loadScene(scenePath(c.path));
    const double rmse = renderAndCompare(scene, technique, settings(128, 16)).errors.visibility.rmse;
    const double vssm = renderAndCompare(scene, "vssm", settings(128, 16)).errors.visibility.rmse;
    std::printf("%s: %s %.4f, vssm %.4f\n", c.path, technique, rmse, vssm);
    ::testing::Test::RecordProperty(sceneTestName(c.path) + "_" + technique, std::to_string(rmse));
    EXPECT_LE(rmse, c.gate) << c.path;
    EXPECT_LE(rmse, factor * vssm) << c.path;
  }
}

}  // namespace penumbra::test
