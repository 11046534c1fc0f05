#include "pipeline/compare.h"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"

namespace penumbra {
namespace {

// Stacks images vertically (all the same width and channel count).
Image stack(const std::vector<const Image*>& images) {
  Image out(images.front()->width, 0, images.front()->channels);
  for (auto* im : images) {
    out.height += im->height;
    out.data.insert(out.data.end(), im->data.begin(), im->data.end());
  }
  return out;
}

template <class T>
std::vector<T> repeat(const std::vector<T>& v, std::size_t times) {
  std::vector<T> out;
  for (std::size_t i = 0; i < times; ++i) out.insert(out.end(), v.begin(), v.end());
  return out;
}

}  // namespace

TechniqueErrors measureErrors(const FrameResult& frame, const FrameResult& ref) {
  PENUMBRA_CHECK(frame.lights.size() == ref.lights.size(), "frames of different scenes");
  TechniqueErrors e;
  const auto& valid = ref.gbuffer.valid;
  std::size_t n = valid.size(), L = ref.lights.size();

  std::vector<const Image*> a, b;
  std::vector<std::uint8_t> band;
  std::vector<std::uint8_t> anyBand(n, 0);
  for (std::size_t l = 0; l < L; ++l) {
    a.push_back(&frame.lights[l].visibility);
    b.push_back(&ref.lights[l].visibility);
    auto m = edgeBandMask(ref.lights[l].visibility, 1);
    band.insert(band.end(), m.begin(), m.end());
    for (std::size_t i = 0; i < n; ++i) anyBand[i] |= m[i];
  }
  Image va = stack(a), vb = stack(b);
  auto validL = repeat(valid, L);
  e.visibility = compareImages(va, vb, {}, validL);
  e.visibilityOutsideBand = compareImages(va, vb, band, validL);
  e.shaded = compareImages(frame.color, ref.color, {}, valid);
  e.shadedOutsideBand = compareImages(frame.color, ref.color, anyBand, valid);

  std::int64_t agree = 0, pairs = 0;
  for (std::size_t l = 0; l < L; ++l) {
    const auto& fa = frame.lights[l];
    const auto& fb = ref.lights[l];
    float decision = 0.5f / float(std::max(1, fb.samples));
    for (std::size_t i = 0; i < n; ++i) {
      if (!valid[i] || band[l * n + i]) continue;
      float d = 0.0f;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(fa.visibility.data[i * 3 + c] - fb.visibility.data[i * 3 + c]));
      if (d > decision) ++e.misclassifiedPixels;
      if (fa.perSample.empty() || fb.perSample.empty() || fa.samples != fb.samples) continue;
      for (int k = 0; k < fb.samples; ++k) {
        std::size_t idx = i * std::size_t(fb.samples) + std::size_t(k);
        agree += std::abs(fa.perSample[idx] - fb.perSample[idx]) < 1e-3f;
        ++pairs;
      }
    }
  }
  if (pairs > 0) e.sampleAgreement = double(agree) / double(pairs);
  e.samplePairs = pairs;
  return e;
}

void writeFrame(const std::string& path, const FrameResult& frame, float exposure) {
  auto ext = std::filesystem::path(path).extension().string();
  if (ext == ".png") {
    writePng(path, frame.color, exposure);
  } else if (ext == ".exr") {
    std::vector<std::string> names;
    std::vector<ExrLayer> layers{{"", &frame.color}};
    for (std::size_t l = 0; l < frame.lights.size(); ++l)
      names.push_back(l == 0 ? "visibility" : "visibility" + std::to_string(l));
    for (std::size_t l = 0; l < frame.lights.size(); ++l) layers.push_back({names[l], &frame.lights[l].visibility});
    writeExr(path, layers);
  } else {
    throw Error(path, "output must end in .exr or .png");
  }
}

nlohmann::json frameSummary(const FrameResult& frame) {
  nlohmann::json stages = nlohmann::json::object();
  for (auto& s : frame.timer.stages()) stages[s.stage] = s.ms;
  nlohmann::json stats = nlohmann::json::object();
  for (auto& [k, v] : frame.statistics) stats[k] = v;
  return {{"stagesMs", stages}, {"statistics", stats}, {"totalMs", frame.timer.total()}, {"memoryBytes", frame.memoryBytes},
          {"width", frame.color.width}, {"height", frame.color.height}};
}

nlohmann::json errorsJson(const TechniqueErrors& e) {
  auto stats = [](const ErrorStats& s) {
    return nlohmann::json{{"rmse", s.rmse}, {"meanAbs", s.meanAbs}, {"maxAbs", s.maxAbs},
                          {"pixelsOver1_255", s.pixelsOver}, {"pixels", s.pixelsCounted}};
  };
  nlohmann::json j{{"visibility", stats(e.visibility)}, {"visibilityOutsideBand", stats(e.visibilityOutsideBand)},
                   {"shaded", stats(e.shaded)}, {"shadedOutsideBand", stats(e.shadedOutsideBand)},
                   {"misclassifiedPixelsOutsideBand", e.misclassifiedPixels}};
  if (e.sampleAgreement >= 0.0) j["sampleAgreementOutsideBand"] = e.sampleAgreement;
  return j;
}

CompareReport compareTechniques(gl::Context& context, const Scene& scene, const RenderSettings& settings,
                                const std::vector<std::string>& techniques, const std::string& outDir,
                                const TechniqueParams& params) {
  // Every technique is created (and its parameters checked) before the long renders start.
  std::vector<std::unique_ptr<Technique>> created;
  for (auto& name : techniques) created.push_back(makeTechnique(name, params));
  params.checkConsumed();
  namespace fs = std::filesystem;
  Renderer renderer(context, scene, settings);
  auto write = [&](const std::string& name, const FrameResult& f) {
    if (outDir.empty()) return;
    writeFrame((fs::path(outDir) / (name + ".exr")).string(), f);
    writeFrame((fs::path(outDir) / (name + ".png")).string(), f);
  };
  PLOG_INFO("[1/{}] reference: raytrace ({} samples)", techniques.size() + 1, settings.sampling.count);
  auto refTech = makeTechnique("raytrace");
  FrameResult ref = renderer.render(*refTech);
  write("raytrace", ref);

  CompareReport report;
  auto& j = report.json;
  j["scene"] = scene.sourcePath.empty() ? "default" : scene.sourcePath;
  j["renderer"] = context.renderer();
  j["glVersion"] = context.version();
  j["width"] = settings.width;
  j["height"] = settings.height;
  j["samples"] = settings.sampling.count;
  j["strategy"] = toString(settings.sampling.strategy);
  j["pattern"] = toString(settings.sampling.pattern);
  j["seed"] = settings.sampling.seed;
  j["shading"] = toString(settings.shading);
  j["triangles"] = scene.triangleCount();
  j["params"] = params.given();
  j["reference"] = frameSummary(ref);
  j["techniques"] = nlohmann::json::array();
  report.table = fmt::format("{:<20} {:>10} {:>10} {:>10} {:>10} {:>12}\n", "technique", "total ms",
                             "vis RMSE", "vis max", "img RMSE", "misclass px");
  report.table += fmt::format("{:<20} {:>10.1f} {:>10} {:>10} {:>10} {:>12}\n", "raytrace (ref)",
                              ref.timer.total(), "-", "-", "-", "-");
  for (std::size_t i = 0; i < techniques.size(); ++i) {
    const auto& name = techniques[i];
    PLOG_INFO("[{}/{}] {}", i + 2, techniques.size() + 1, name);
    auto& tech = created[i];
    RenderSettings s = settings;
    if (s.shading == ShadingMode::PerSample && !tech->providesPerSample()) s.shading = ShadingMode::Modulate;
    FrameResult f = (s.shading == settings.shading) ? renderer.render(*tech) : Renderer(context, scene, s).render(*tech);
    tech.reset();  // its render targets go before the next technique allocates its own
    TechniqueErrors e = measureErrors(f, ref);
    write(name, f);
    if (!outDir.empty()) {
      Image heat = errorHeatMap(f.lights[0].visibility, ref.lights[0].visibility, 0.25f);
      writePng((fs::path(outDir) / (name + "_heat.png")).string(), heat);
    }
    nlohmann::json t = frameSummary(f);
    t["name"] = name;
    t["shading"] = toString(s.shading);
    t["errors"] = errorsJson(e);
    j["techniques"].push_back(t);
    report.visibilityRmse.emplace_back(name, e.visibility.rmse);
    report.table += fmt::format("{:<20} {:>10.1f} {:>10.4f} {:>10.4f} {:>10.4g} {:>12}\n", name, f.timer.total(),
                                e.visibility.rmse, e.visibility.maxAbs, e.shaded.rmse, e.misclassifiedPixels);
  }
  return report;
}

}  // namespace penumbra
