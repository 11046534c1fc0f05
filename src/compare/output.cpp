#include "compare/output.h"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "compare/compare.h"
#include "core/error.h"
#include "core/image_io.h"

namespace penumbra {
namespace {

nlohmann::json spreadJson(const Spread& s) { return {{"median", s.median}, {"min", s.min}, {"max", s.max}}; }

}  // namespace

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
  nlohmann::json stages = nlohmann::json::object(), harness = nlohmann::json::object(),
                 counts = nlohmann::json::object();
  for (auto& s : frame.timer.stages()) {
    (s.kind == StageKind::Harness ? harness : stages)[s.stage] = s.ms;
    if (s.counted && s.kind == StageKind::Technique) counts[s.stage] = countsJson(s.counts);
  }
  nlohmann::json stats = nlohmann::json::object();
  for (auto& [k, v] : frame.statistics) stats[k] = v;
  nlohmann::json j = {{"stagesMs", stages},
                      {"statistics", stats},
                      {"totalMs", frame.timer.total()},
                      {"harnessStagesMs", harness},
                      {"harnessMs", frame.timer.harnessTotal()},
                      {"memoryBytes", frame.memoryBytes},
                      {"width", frame.color.width},
                      {"height", frame.color.height}};
  if (!counts.empty()) j["pipelineStatistics"] = counts;
  return j;
}

nlohmann::json countsJson(const PipelineCounts& c) {
  nlohmann::json j = nlohmann::json::object();
  for (auto& [k, v] : c.fields()) j[k] = v;
  return j;
}

nlohmann::json errorsJson(const TechniqueErrors& e) {
  auto stats = [](const ErrorStats& s) {
    return nlohmann::json{{"rmse", s.rmse},
                          {"meanAbs", s.meanAbs},
                          {"maxAbs", s.maxAbs},
                          {"pixelsOver1_255", s.pixelsOver},
                          {"pixels", s.pixelsCounted}};
  };
  nlohmann::json j{{"visibility", stats(e.visibility)},
                   {"visibilityOutsideBand", stats(e.visibilityOutsideBand)},
                   {"shaded", stats(e.shaded)},
                   {"shadedOutsideBand", stats(e.shadedOutsideBand)},
                   {"misclassifiedPixelsOutsideBand", e.misclassifiedPixels},
                   {"unshadowedPixels", e.unshadowedPixels},
                   {"visibilityExceptUnshadowed", stats(e.visibilityExceptUnshadowed)}};
  if (e.sampleAgreement >= 0.0) {
    j["sampleAgreementOutsideBand"] = e.sampleAgreement;
    j["sampleMismatchesOutsideBand"] = e.sampleMismatches;
  }
  return j;
}

void writeRunImages(const RunImages& out, const std::string& base, const FrameResult& f, const FrameResult* against,
                    const Image* flip, CompareRun& run) {
  namespace fs = std::filesystem;
  fs::path dir(out.dir);
  if (out.exr) writeFrame((dir / (base + ".exr")).string(), f);
  if (!out.images) return;
  writeFrame((dir / (base + ".png")).string(), f);
  run.image = base + ".png";
  if (against) {
    writePng((dir / (base + "_heat.png")).string(),
             errorHeatMap(f.lights[0].visibility, against->lights[0].visibility, 0.25f));
    run.heat = base + "_heat.png";
  }
  if (flip) {
    writePng((dir / (base + "_flip.png")).string(), flipHeatMap(*flip));
    run.flipHeat = base + "_flip.png";
  }
  // Pixels left unshadowed by design (outside the shadow maps' frustum), white on black.
  std::vector<std::uint8_t> any(f.gbuffer.valid.size(), 0);
  bool some = false;
  for (const auto& l : f.lights)
    for (std::size_t i = 0; i < l.unshadowed.size() && i < any.size(); ++i) some |= (any[i] |= l.unshadowed[i]) != 0;
  if (some) {
    Image mask(f.color.width, f.color.height, 3);
    for (std::size_t i = 0; i < any.size(); ++i)
      for (int c = 0; c < 3; ++c) mask.data[i * 3 + std::size_t(c)] = any[i] ? 1.0f : 0.0f;
    writePng((dir / (base + "_unshadowed.png")).string(), mask);
    run.unshadowedMask = base + "_unshadowed.png";
  }
  for (std::size_t i = 0; i < out.insets.size(); ++i) {
    const Inset& r = out.insets[i];
    int zoom = std::max(1, 160 / std::max(r.w, r.h));
    std::string name = fmt::format("insets/{}_{}.png", base, i);
    writePng((dir / name).string(), crop(f.color, r, zoom));
    run.insetImages.push_back(name);
  }
}

nlohmann::json CompareResult::json() const {
  nlohmann::json j = info;
  nlohmann::json presetsJson = nlohmann::json::array();
  for (auto& p : presets)
    presetsJson.push_back(
        {{"label", p.label}, {"width", p.width}, {"height", p.height}, {"samples", p.samples}, {"params", p.params}});
  j["presets"] = presetsJson;
  nlohmann::json insetJson = nlohmann::json::array();
  for (auto& r : insets) insetJson.push_back({r.x, r.y, r.w, r.h});
  j["insets"] = insetJson;
  j["insetSource"] = insetSource;
  nlohmann::json runsJson = nlohmann::json::array();
  for (auto& r : runs) {
    nlohmann::json stages = nlohmann::json::object(), spreads = nlohmann::json::object(),
                   stats = nlohmann::json::object();
    for (auto& [k, v] : r.stages) stages[k] = v.median, spreads[k] = spreadJson(v);
    for (auto& [k, v] : r.statistics) stats[k] = v;
    nlohmann::json harness = nlohmann::json::object();
    for (auto& [k, v] : r.harnessStages) harness[k] = v.median;
    nlohmann::json t{{"name", r.technique},
                     {"family", toString(r.family)},
                     {"preset", presets[r.preset].label},
                     {"presetIndex", r.preset},
                     {"reference", r.reference},
                     {"params", r.params},
                     {"samples", presets[r.preset].samples},
                     {"width", presets[r.preset].width},
                     {"height", presets[r.preset].height},
                     {"shading", r.shading},
                     {"stagesMs", stages},
                     {"stagesSpreadMs", spreads},
                     {"totalMs", r.total.median},
                     {"totalSpreadMs", spreadJson(r.total)},
                     {"harnessStagesMs", harness},
                     {"harnessMs", r.harness.median},
                     {"harnessSpreadMs", spreadJson(r.harness)},
                     {"prepareMs", r.prepareMs},
                     {"memoryBytes", r.memoryBytes},
                     {"statistics", stats},
                     {"errors", errorsJson(r.errors)},
                     {"image", r.image},
                     {"heat", r.heat},
                     {"flipHeat", r.flipHeat},
                     {"unshadowedMask", r.unshadowedMask},
                     {"insets", r.insetImages},
                     {"status", r.failed ? "failed" : "ok"}};
    if (r.failed) {
      // No numbers for a failed run: its timings and errors were never measured.
      for (const char* k : {"stagesMs", "stagesSpreadMs", "totalMs", "totalSpreadMs", "prepareMs", "memoryBytes",
                            "statistics", "errors", "harnessStagesMs", "harnessMs", "harnessSpreadMs"})
        t.erase(k);
      t["error"] = r.failure;
    }
    if (!r.failed && !r.counts.empty()) {
      nlohmann::json counts = nlohmann::json::object();
      for (auto& [k, c] : r.counts) counts[k] = countsJson(c);
      t["pipelineStatistics"] = {{"stages", counts}, {"total", countsJson(totalCounts(r))}};
    }
    if (r.converged) t["convergedErrors"] = errorsJson(*r.converged);
    if (r.referenceNoise) {
      nlohmann::json stats = nlohmann::json::object();
      for (auto& [k, v] : r.referenceStatistics) stats[k] = v;
      t["convergedReferenceNoise"] = {{"visibilityRmse", r.referenceNoise->visibility},
                                      {"shadedRmse", r.referenceNoise->shaded},
                                      {"statistics", stats},
                                      {"meaning",
                                       "the RMSE the converged reference's own noise puts into every error "
                                       "against it: the error floor"}};
    }
    if (r.flip) t["flip"] = {{"mean", *r.flip}, {"against", r.converged ? "converged" : "same-sample"}};
    if (r.flicker >= 0.0)
      t["temporal"] = {
          {"flicker", r.flicker}, {"referenceMotion", r.referenceMotion}, {"meanVisibilityRmse", r.meanFrameRmse}};
    runsJson.push_back(t);
  }
  j["runs"] = runsJson;
  return j;
}

}  // namespace penumbra
