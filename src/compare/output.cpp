#include "compare/output.h"

#include <algorithm>
#include <cmath>
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
  if (std::any_of(e.sampleAgreementByRing.begin(), e.sampleAgreementByRing.end(), [](double a) { return a >= 0.0; })) {
    nlohmann::json rings = nlohmann::json::array();
    for (double a : e.sampleAgreementByRing) rings.push_back(a >= 0.0 ? nlohmann::json(a) : nlohmann::json());
    j["sampleAgreementByRing"] = rings;
  }
  return j;
}

namespace {

Spread spreadFrom(const nlohmann::json& j) {
  return {j.at("median").get<double>(), j.at("min").get<double>(), j.at("max").get<double>()};
}

TechniqueErrors errorsFrom(const nlohmann::json& j) {
  auto stats = [](const nlohmann::json& s) {
    ErrorStats e;
    // A NaN error is written as null (JSON has no NaN) and read back as NaN.
    auto number = [&](const char* k) { return s.at(k).is_null() ? std::nan("") : s.at(k).get<double>(); };
    e.rmse = number("rmse"), e.meanAbs = number("meanAbs"), e.maxAbs = number("maxAbs");
    e.pixelsOver = s.at("pixelsOver1_255").get<std::int64_t>(), e.pixelsCounted = s.at("pixels").get<std::int64_t>();
    return e;
  };
  TechniqueErrors e;
  e.visibility = stats(j.at("visibility")), e.visibilityOutsideBand = stats(j.at("visibilityOutsideBand"));
  e.shaded = stats(j.at("shaded")), e.shadedOutsideBand = stats(j.at("shadedOutsideBand"));
  e.misclassifiedPixels = j.at("misclassifiedPixelsOutsideBand").get<std::int64_t>();
  e.unshadowedPixels = j.at("unshadowedPixels").get<std::int64_t>();
  e.visibilityExceptUnshadowed = stats(j.at("visibilityExceptUnshadowed"));
  if (j.contains("sampleAgreementOutsideBand")) {
    e.sampleAgreement = j.at("sampleAgreementOutsideBand").get<double>();
    e.sampleMismatches = j.at("sampleMismatchesOutsideBand").get<std::int64_t>();
  }
  if (j.contains("sampleAgreementByRing")) {
    const auto& rings = j.at("sampleAgreementByRing");
    for (std::size_t r = 0; r < e.sampleAgreementByRing.size() && r < rings.size(); ++r)
      e.sampleAgreementByRing[r] = rings[r].is_null() ? -1.0 : rings[r].get<double>();
  }
  return e;
}

PipelineCounts countsFrom(const nlohmann::json& j) {
  PipelineCounts c;
  c.primitivesSubmitted = j.value("primitives", std::uint64_t(0)), c.vertexInvocations = j.value("vertex", 0ull);
  c.geometryInvocations = j.value("geometry", 0ull), c.clippingOutputPrimitives = j.value("rasterized", 0ull);
  c.fragmentInvocations = j.value("fragment", 0ull), c.computeInvocations = j.value("compute", 0ull);
  return c;
}

}  // namespace

CompareRun runFromJson(const nlohmann::json& j, std::size_t preset, const std::string& where) {
  CompareRun r;
  try {
    r.technique = j.at("name").get<std::string>();
    r.family = TechniqueFamily::Hard;
    const std::string family = j.at("family").get<std::string>();
    bool known = false;
    for (TechniqueFamily f : kTechniqueFamilies)
      if (family == toString(f)) r.family = f, known = true;
    if (!known) throw Error(where, "a run of an unknown family '" + family + "'");
    r.preset = preset;
    r.reference = j.at("reference").get<bool>();
    r.params = j.at("params").get<std::vector<std::string>>();
    r.shading = j.at("shading").get<std::string>();
    r.image = j.value("image", ""), r.heat = j.value("heat", ""), r.flipHeat = j.value("flipHeat", "");
    r.unshadowedMask = j.value("unshadowedMask", "");
    r.insetImages = j.value("insets", std::vector<std::string>{});
    if (j.at("status").get<std::string>() == "failed") {
      r.failed = true;
      r.failure = j.at("error").get<std::string>();
      return r;
    }
    for (auto& [k, v] : j.at("stagesSpreadMs").items()) r.stages.emplace_back(k, spreadFrom(v));
    r.total = spreadFrom(j.at("totalSpreadMs"));
    for (auto& [k, v] : j.at("harnessStagesMs").items()) r.harnessStages.emplace_back(k, Spread{v, v, v});
    r.harness = spreadFrom(j.at("harnessSpreadMs"));
    r.prepareMs = j.at("prepareMs").get<double>();
    r.memoryBytes = j.at("memoryBytes").get<std::size_t>();
    for (auto& [k, v] : j.at("statistics").items()) r.statistics.emplace_back(k, v.get<double>());
    r.errors = errorsFrom(j.at("errors"));
    r.notes = j.value("notes", std::vector<std::string>{});
    if (j.contains("pipelineStatistics"))
      for (auto& [k, v] : j.at("pipelineStatistics").at("stages").items()) r.counts.emplace_back(k, countsFrom(v));
    if (j.contains("convergedErrors")) r.converged = errorsFrom(j.at("convergedErrors"));
    if (j.contains("convergedReferenceNoise")) {
      const auto& n = j.at("convergedReferenceNoise");
      r.referenceNoise = ReferenceNoise{n.at("visibilityRmse").get<double>(), n.at("shadedRmse").get<double>()};
      for (auto& [k, v] : n.at("statistics").items()) r.referenceStatistics.emplace_back(k, v.get<double>());
    }
    if (j.contains("flip"))
      r.flip = j.at("flip").at("mean").is_null() ? std::nan("") : j.at("flip").at("mean").get<double>();
    if (j.contains("temporal")) {
      const auto& t = j.at("temporal");
      r.flicker = t.at("flicker").get<double>(), r.referenceMotion = t.at("referenceMotion").get<double>();
      r.meanFrameRmse = t.at("meanVisibilityRmse").get<double>();
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(where, std::string("not a run of a comparison: ") + e.what());
  }
  return r;
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
                     {"notes", r.notes},
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
                            "statistics", "notes", "errors", "harnessStagesMs", "harnessMs", "harnessSpreadMs"})
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
