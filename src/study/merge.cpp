#include "study/merge.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "compare/compare.h"
#include "compare/output.h"
#include "compare/plot.h"
#include "compare/report.h"
#include "core/error.h"
#include "core/files.h"
#include "core/machine.h"
#include "study/plan.h"
#include "study/run.h"
#include "techniques/registry.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace penumbra::study {
namespace {

struct Row {
  const Job* job;
  json row;  // null: missing
  bool ok() const { return !row.is_null() && row.value("status", "") == "ok"; }
};

// A job's scene with its variant ("semi-opaque.json opacity=1"): the unit of a scene report.
std::string sceneKey(const Job& j) {
  std::string key = j.scene;
  for (const auto& v : j.variant) key += " " + v;
  return key;
}

std::string configLabel(const Job& j) {
  std::string label = fmt::format("{} samples={} {}x{} seed={} {}", sceneKey(j), j.samples, j.size.width, j.size.height,
                                  j.seed, j.strategy);
  if (j.lightScale != 1.0) label += fmt::format(" light={}", j.lightScale);
  if (j.shading != "ratio") label += " " + j.shading;
  if (j.pattern != "correlated") label += " " + j.pattern;
  return label;
}

// ---- results.jsonl and results.csv

std::string number(const json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || j[key].is_null()) return "";
  return j[key].is_number() ? fmt::format("{}", j[key].get<double>()) : j[key].dump();
}

std::string resultsCsv(const std::vector<Row>& rows) {
  std::string csv =
      "id,kind,status,scene,variant,scene_name,technique,params,samples,width,height,seed,strategy,light_scale,"
      "shading,pattern,total_ms,total_ms_min,"
      "total_ms_max,prepare_ms,memory_bytes,visibility_rmse,visibility_rmse_outside_band,shaded_rmse,"
      "converged_visibility_rmse,converged_shaded_rmse,flip,sample_agreement,sample_agreement_ring0,"
      "sample_agreement_ring1,sample_agreement_ring2,sample_agreement_ring3,triangles,misclassified_pixels,"
      "unshadowed_pixels,reference_noise_visibility,date,seconds,renderer,gl_version,host,error\n";
  for (const Row& r : rows) {
    if (r.row.is_null()) continue;
    const Job& j = *r.job;
    const json& row = r.row;
    const json result = row.value("result", json::object());
    const json errors = result.value("errors", json::object()), conv = result.value("convergedErrors", json::object());
    const json total = result.value("totalSpreadMs", json::object());
    const json noise = result.value("convergedReferenceNoise", result.value("noise", json::object()));
    const auto joined = [](const std::vector<std::string>& v) { return fmt::format("{}", fmt::join(v, " ")); };
    const json rings = errors.value("sampleAgreementByRing", json::array());
    const auto ring = [&](std::size_t r) {
      return r < rings.size() && rings[r].is_number() ? fmt::format("{}", rings[r].get<double>()) : std::string();
    };
    const std::vector<std::string> fields = {j.id,
                                             j.kind,
                                             row.value("status", "?"),
                                             j.scene,
                                             joined(j.variant),
                                             row.value("info", json::object()).value("sceneName", ""),
                                             j.technique,
                                             joined(j.params),
                                             std::to_string(j.samples),
                                             number(row.value("info", json::object()), "width"),
                                             number(row.value("info", json::object()), "height"),
                                             std::to_string(j.seed),
                                             j.strategy,
                                             fmt::format("{}", j.lightScale),
                                             j.shading,
                                             j.pattern,
                                             number(total, "median"),
                                             number(total, "min"),
                                             number(total, "max"),
                                             number(result, "prepareMs"),
                                             number(result, "memoryBytes"),
                                             number(errors.value("visibility", json::object()), "rmse"),
                                             number(errors.value("visibilityOutsideBand", json::object()), "rmse"),
                                             number(errors.value("shaded", json::object()), "rmse"),
                                             number(conv.value("visibility", json::object()), "rmse"),
                                             number(conv.value("shaded", json::object()), "rmse"),
                                             number(result.value("flip", json::object()), "mean"),
                                             number(errors, "sampleAgreementOutsideBand"),
                                             ring(0),
                                             ring(1),
                                             ring(2),
                                             ring(3),
                                             number(row.value("info", json::object()), "triangles"),
                                             number(errors, "misclassifiedPixelsOutsideBand"),
                                             number(errors, "unshadowedPixels"),
                                             number(noise, "visibilityRmse"),
                                             row.value("date", ""),
                                             number(row, "seconds"),
                                             row.value("renderer", ""),
                                             row.value("glVersion", ""),
                                             row.value("machine", json::object()).value("host", ""),
                                             row.value("error", "")};
    std::string line;
    for (const auto& f : fields) line += (line.empty() ? "" : ",") + csvField(f);
    csv += line + "\n";
  }
  return csv;
}

// ---- per-scene reports

// The axes that vary across the study's configurations, for preset labels.
struct Axes {
  bool sizes = false, seeds = false, strategies = false, lightScales = false, shadings = false, patterns = false;
  // Whether the headline names its presets by label (an axis but samples and seeds varies).
  bool labelled() const { return sizes || strategies || lightScales || shadings || patterns; }
};

Axes axesOf(const std::vector<Row>& rows) {
  std::set<std::pair<int, int>> sizes;
  std::set<std::uint32_t> seeds;
  std::set<std::string> strategies, shadings, patterns;
  std::set<double> lightScales;
  for (const Row& r : rows) {
    if (r.job->kind == "converged") continue;
    sizes.insert({r.job->size.width, r.job->size.height});
    seeds.insert(r.job->seed);
    strategies.insert(r.job->strategy);
    lightScales.insert(r.job->lightScale);
    shadings.insert(r.job->shading);
    patterns.insert(r.job->pattern);
  }
  return {sizes.size() > 1,       seeds.size() > 1,    strategies.size() > 1,
          lightScales.size() > 1, shadings.size() > 1, patterns.size() > 1};
}

// The preset axes a study can have, in the order of a preset's label.
constexpr const char* kPresetAxes[] = {"samples", "size", "light", "shading", "pattern", "seed", "strategy"};

ComparePreset presetOf(const Job& j, const json& info, const Axes& axes) {
  ComparePreset p;
  p.samples = j.samples;
  p.width = info.value("width", j.size.width), p.height = info.value("height", j.size.height);
  p.values = {{"samples", std::to_string(j.samples)}};
  if (axes.sizes) p.values.push_back({"size", fmt::format("{}x{}", p.width, p.height)});
  if (axes.lightScales) p.values.push_back({"light", fmt::format("{}", j.lightScale)});
  if (axes.shadings) p.values.push_back({"shading", j.shading});
  if (axes.patterns) p.values.push_back({"pattern", j.pattern});
  if (axes.seeds) p.values.push_back({"seed", std::to_string(j.seed)});
  if (axes.strategies) p.values.push_back({"strategy", j.strategy});
  for (const auto& [k, v] : p.values) p.label += (p.label.empty() ? "" : " ") + k + "=" + v;
  return p;
}

// The comparison of one scene, rebuilt from its reference and technique rows (plan order:
// each configuration's reference before its techniques), the images those of the jobs' folders.
struct SceneReport {
  std::string name, folder;
  CompareResult result;
  std::vector<std::string> statisticsFrom;  // per run: "a profiled frame (...)" or ""
  std::vector<std::uint32_t> presetSeeds;   // per preset
  std::size_t missing = 0, rows = 0;
};

SceneReport sceneReport(const std::vector<const Row*>& rows, const Axes& axes, const fs::path& dir,
                        const fs::path& reportDir) {
  SceneReport s;
  std::map<std::string, std::size_t> presetOfConfig;
  for (const Row* r : rows) {
    ++s.rows;
    if (r->row.is_null()) {
      ++s.missing;
      continue;
    }
    const Job& j = *r->job;
    json info = r->row.value("info", json::object());
    const std::string key = fmt::format("{}/{}x{}/{}/{}/{}/{}/{}", j.samples, j.size.width, j.size.height, j.seed,
                                        j.strategy, j.lightScale, j.shading, j.pattern);
    auto [it, added] = presetOfConfig.emplace(key, s.result.presets.size());
    if (added) {
      s.result.presets.push_back(presetOf(j, info, axes));
      s.presetSeeds.push_back(j.seed);
    }
    const std::string where = (dir / "jobs" / j.id / "row.json").string();
    CompareRun run;
    if (r->ok()) {
      run = runFromJson(r->row.at("result"), it->second, where);
    } else {
      run.technique = j.technique, run.preset = it->second, run.params = j.params, run.failed = true;
      run.failure = r->row.value("error", "?");
      run.reference = j.kind == "reference";
      // Its family from the table (a technique named in a plan the table no longer has keeps
      // the default).
      for (const TechniqueInfo& t : techniqueTable())
        if (t.name == j.technique) run.family = t.family;
    }
    const std::string rel = fs::relative(dir / "jobs" / j.id, reportDir).string() + "/";
    for (std::string* f : {&run.image, &run.heat, &run.flipHeat, &run.unshadowedMask})
      if (!f->empty()) *f = rel + *f;
    for (std::string& f : run.insetImages) f = rel + f;
    if (s.result.info.is_null() && r->ok()) {
      s.result.info = info;
      for (const auto& i : info.value("insets", json::array()))
        s.result.insets.push_back({i[0].get<int>(), i[1].get<int>(), i[2].get<int>(), i[3].get<int>()});
      s.result.insetSource = info.value("insetSource", "chosen");
      s.name = info.value("sceneName", j.scene);
      for (const auto& v : j.variant) s.name += " " + v;
    }
    s.result.runs.push_back(std::move(run));
    s.statisticsFrom.push_back(r->ok() ? r->row.at("result").value("statisticsFrom", "") : "");
  }
  if (s.result.info.is_null()) s.result.info = json::object();
  if (!s.name.empty()) s.result.info["sceneName"] = s.name;
  for (const char* k : {"presets", "insets", "insetSource", "incomplete"}) s.result.info.erase(k);
  json sweeps = json::array();
  for (const char* axis : kPresetAxes) {
    std::vector<std::string> values;
    for (const auto& p : s.result.presets)
      for (const auto& [k, v] : p.values)
        if (k == axis && std::find(values.begin(), values.end(), v) == values.end()) values.push_back(v);
    if (values.size() > 1) sweeps.push_back({{"key", axis}, {"values", values}});
  }
  s.result.info["sweeps"] = sweeps;
  if (s.missing > 0) s.result.info["incomplete"] = fmt::format("{} of {} rows", s.rows - s.missing, s.rows);
  return s;
}

// ---- the headline across scenes

// Per technique (its name and parameters) and preset of the headline (samples, and size where
// the study has several): sums of logs over the scenes, per seed.
struct Acc {
  double logMs = 0, logErr = 0, logRatio = 0;
  int n = 0, front = 0;
  bool sameSample = false;  // an error against the same-sample reference (no converged one there)
};

struct Headline {
  CompareResult plot;  // the geometric means as runs: the same plot and summary as a scene's
  std::string text, md, summary;
};

std::string runName(const CompareRun& r) {
  std::string name = r.technique;
  for (const auto& p : r.params) name += " " + p;
  return name;
}

Headline headlineOf(const std::vector<SceneReport>& scenes, const Axes& axes) {
  std::map<std::pair<std::string, std::string>, std::map<std::uint32_t, Acc>> acc;  // (name, preset label)
  std::map<std::pair<std::string, std::string>, std::vector<std::string>> failedOn;
  std::map<std::string, TechniqueFamily> family;
  std::vector<std::string> order;
  std::vector<ComparePreset> presets;  // of the headline
  auto headlinePreset = [&](const ComparePreset& p) {
    ComparePreset h;
    h.samples = p.samples, h.width = p.width, h.height = p.height;
    // Every axis but the seed: the seeds are what the spread is over.
    h.values = p.values;
    h.values.erase(std::remove_if(h.values.begin(), h.values.end(), [](auto& v) { return v.first == "seed"; }),
                   h.values.end());
    for (const auto& [k, v] : h.values) h.label += (h.label.empty() ? "" : " ") + k + "=" + v;
    auto it = std::find_if(presets.begin(), presets.end(), [&](auto& q) { return q.label == h.label; });
    if (it == presets.end()) presets.push_back(h);
    return h.label;
  };
  for (const SceneReport& s : scenes) {
    const CompareResult& r = s.result;
    const auto front = paretoRuns(r);
    for (std::size_t i = 0; i < r.runs.size(); ++i) {
      const CompareRun& run = r.runs[i];
      const std::string name = runName(run), label = headlinePreset(r.presets[run.preset]);
      if (std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
      family[name] = run.family;
      if (run.failed) {
        failedOn[{name, label}].push_back(s.name);
        continue;
      }
      const auto plotted = plottedRuns(r);
      if (std::find(plotted.begin(), plotted.end(), i) == plotted.end()) continue;
      const auto raytrace = std::find_if(r.runs.begin(), r.runs.end(), [&](const CompareRun& x) {
        return x.reference && x.preset == run.preset && !x.failed;
      });
      if (raytrace == r.runs.end()) continue;
      Acc& a = acc[{name, label}][s.presetSeeds[run.preset]];
      a.logRatio += std::log(run.total.median / raytrace->total.median);
      a.logMs += std::log(run.total.median);
      a.logErr += std::log(std::max(run.plotError(), 1e-6));
      a.sameSample = a.sameSample || !run.converged;
      a.n += 1;
      a.front += std::find(front.begin(), front.end(), i) != front.end();
    }
  }
  std::sort(presets.begin(), presets.end(), [](auto& a, auto& b) {
    return std::tie(a.width, a.height, a.samples, a.label) < std::tie(b.width, b.height, b.samples, b.label);
  });
  const bool converged = std::any_of(scenes.begin(), scenes.end(), [](auto& s) { return s.result.hasConverged(); });
  const std::string against = converged ? "converged" : "same-sample reference";
  Headline h;
  h.plot.info = {{"sceneName", fmt::format("geometric mean over {} scenes", scenes.size())}};
  h.plot.presets = presets;
  h.md = fmt::format(
      "| technique | {} | ms (geo. mean) | x raytrace time | visibility RMSE vs {} (geo. mean) | on the Pareto front "
      "| scenes |\n|---|---|---|---|---|---|---|\n",
      axes.labelled() ? "preset" : "samples", against);
  // Columns wide enough for a [min, max] over the seeds.
  const int wMs = axes.seeds ? 22 : 10, wX = axes.seeds ? 20 : 11, wErr = axes.seeds ? 26 : 24;
  // And for the longest name and preset.
  std::size_t wName = 24, wPreset = 22;
  for (const std::string& name : order) wName = std::max(wName, name.size());
  for (const ComparePreset& p : presets) wPreset = std::max(wPreset, axes.labelled() ? p.label.size() : 0);
  h.text = fmt::format(
      "Headline: geometric mean over {} scenes (or those named){}\n{:<{}} {:>{}} {:>{}} {:>{}} {:>{}} {:>8}  {}\n",
      scenes.size(), axes.seeds ? "; [min, max] over seeds" : "", "technique", wName,
      axes.labelled() ? "preset" : "samples", wPreset, "ms", wMs, "x raytrace", wX, "RMSE vs " + against, wErr, "front",
      "scenes");
  for (const std::string& name : order)
    for (std::size_t pi = 0; pi < presets.size(); ++pi) {
      const ComparePreset& p = presets[pi];
      const std::string shown = axes.labelled() ? p.label : std::to_string(p.samples);
      const auto bySeed = acc.find({name, p.label});
      const auto failed = failedOn.find({name, p.label});
      if (bySeed == acc.end() && failed == failedOn.end()) continue;
      // Geometric means per seed over the scenes, then over the seeds, with their range.
      std::vector<double> ms, err, ratio;
      int n = 0, front = 0;
      bool sameSample = false;
      if (bySeed != acc.end())
        for (const auto& [seed, a] : bySeed->second) {
          if (a.n == 0) continue;
          ms.push_back(a.logMs / a.n), err.push_back(a.logErr / a.n), ratio.push_back(a.logRatio / a.n);
          n = std::max(n, a.n), front += a.front, sameSample = sameSample || a.sameSample;
        }
      std::string ran = fmt::format("{} of {}", n, scenes.size());
      if (failed != failedOn.end()) {
        auto names = failed->second;
        std::sort(names.begin(), names.end());
        names.erase(std::unique(names.begin(), names.end()), names.end());
        ran += fmt::format(" (failed on {})", fmt::join(names, ", "));
        CompareRun f;
        f.technique = name, f.family = family[name], f.failed = true, f.preset = pi;
        f.failure = fmt::format("on {} (that scene's report says why)", fmt::join(names, ", "));
        h.plot.runs.push_back(f);
      }
      if (ms.empty()) {
        h.text += fmt::format("{:<{}} {:>{}} {:>{}} {:>{}} {:>{}} {:>8}  {}\n", name, wName, shown, wPreset, "-", wMs,
                              "-", wX, "-", wErr, "-", ran);
        h.md += fmt::format("| {} | {} | - | - | - | - | {} |\n", name, shown, ran);
        continue;
      }
      auto mean = [](const std::vector<double>& v) {
        double s = 0;
        for (double x : v) s += x;
        return std::exp(s / double(v.size()));
      };
      auto range = [&](const std::vector<double>& v, const char* f) {
        if (v.size() < 2) return std::string();
        const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
        return fmt::format(" [{}, {}]", fmt::format(fmt::runtime(f), std::exp(*lo)),
                           fmt::format(fmt::runtime(f), std::exp(*hi)));
      };
      const double m = mean(ms), e = mean(err), x = mean(ratio);
      const std::string msText = fmt::format("{:.1f}", m) + range(ms, "{:.1f}");
      // (In a study whose other configurations have a converged reference, one without says so.)
      const std::string errText =
          fmt::format("{:.4f}", e) + range(err, "{:.4f}") + (converged && sameSample ? " (same-sample)" : "");
      const std::string xText = fmt::format("{:.2f}", x) + range(ratio, "{:.2f}");
      const int runs = n * int(ms.size());
      h.text += fmt::format("{:<{}} {:>{}} {:>{}} {:>{}} {:>{}} {:>5}/{}  {}\n", name, wName, shown, wPreset, msText,
                            wMs, xText, wX, errText, wErr, front, runs, ran);
      h.md += fmt::format("| {} | {} | {} | {} | {} | {}/{} | {} |\n", name, shown, msText, xText, errText, front, runs,
                          ran);
      CompareRun run;
      run.technique = name, run.preset = pi, run.reference = name == "raytrace";
      run.family = family[name];
      const auto [lo, hi] = std::minmax_element(ms.begin(), ms.end());
      run.total = {m, std::exp(*lo), std::exp(*hi)};
      TechniqueErrors te;
      te.visibility.rmse = e;
      if (converged)
        run.converged = te;
      else
        run.errors = te;
      h.plot.runs.push_back(run);
    }
  for (const std::string& line : whichTechniqueWhen(h.plot)) h.summary += "- " + line + "\n";
  return h;
}

// ---- per-stage timings

std::string spreadText(const Spread& s) { return fmt::format("{:.2f} [{:.2f}, {:.2f}]", s.median, s.min, s.max); }

// stages.md: per scene and configuration, each run's frame time with its spread over the timed
// frames, its ratio to raytrace's, its memory, every stage's time and its statistics (from a
// profiled frame where the study asked for one): the tables of the timing studies.
std::string stagesMd(const std::vector<SceneReport>& scenes) {
  std::string md =
      "# Per-stage timings\n\nms per frame: median [min, max] over the timed frames (glFinish and a steady clock "
      "around each stage); x raytrace: the frame time over raytrace's at the same configuration; memory: render "
      "targets and buffers.\n";
  for (const SceneReport& s : scenes) {
    md += fmt::format("\n## {}\n", s.name);
    const CompareResult& r = s.result;
    for (std::size_t pi = 0; pi < r.presets.size(); ++pi) {
      const auto raytrace = std::find_if(r.runs.begin(), r.runs.end(), [&](const CompareRun& x) {
        return x.reference && x.preset == pi && !x.failed;
      });
      md += fmt::format(
          "\n### {}\n\n| technique | ms | x raytrace | memory MiB | stages (ms) | statistics |\n"
          "|---|---|---|---|---|---|\n",
          r.presets[pi].label);
      for (std::size_t i = 0; i < r.runs.size(); ++i) {
        const CompareRun& run = r.runs[i];
        if (run.preset != pi) continue;
        if (run.failed) {
          md += fmt::format("| {} | failed: {} | | | | |\n", runName(run), run.failure);
          continue;
        }
        std::vector<std::string> stages, stats;
        for (const auto& [stage, sp] : run.stages) stages.push_back(stage + " " + spreadText(sp));
        for (const auto& [k, v] : run.statistics) stats.push_back(fmt::format("{} {:g}", k, v));
        if (!s.statisticsFrom[i].empty() && s.statisticsFrom[i] != "the last timed frame")
          stats.insert(stats.begin(), "(" + s.statisticsFrom[i] + ")");
        md += fmt::format(
            "| {} | {} | {} | {:.1f} | {} | {} |\n", runName(run), spreadText(run.total),
            raytrace == r.runs.end() ? "-" : fmt::format("{:.2f}", run.total.median / raytrace->total.median),
            double(run.memoryBytes) / (1024.0 * 1024.0), fmt::join(stages, "; "), fmt::join(stats, "; "));
      }
    }
  }
  return md;
}

// ---- light-size curves

// Where the study has several light scales: per scene a chart of each technique's error (the
// headline's: against the converged reference where there is one) against the light's scale,
// one chart per configuration of the other axes, and the tables (light-size.md).
std::string lightSizeCurves(const std::vector<SceneReport>& scenes, const fs::path& root) {
  std::string md = "# Error against light size\n\nEach scene's lights scaled (1: the scene's own).\n";
  bool any = false;
  for (const SceneReport& s : scenes) {
    const CompareResult& r = s.result;
    // (the preset's label without its light) -> technique -> (scale, error), and whether the
    // group's errors are against the converged reference.
    std::map<std::string, std::map<std::string, std::vector<std::pair<double, double>>>> curves;
    std::map<std::string, bool> convergedOf;
    std::map<std::string, TechniqueFamily> family;
    std::vector<std::string> order;
    for (const CompareRun& run : r.runs) {
      if (run.failed || run.reference) continue;
      const ComparePreset& p = r.presets[run.preset];
      std::string others;
      double scale = 1.0;
      for (const auto& [k, v] : p.values)
        if (k == "light")
          scale = std::stod(v);
        else
          others += (others.empty() ? "" : " ") + k + "=" + v;
      const std::string name = runName(run);
      if (std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
      family[name] = run.family;
      curves[others][name].emplace_back(scale, run.plotError());
      convergedOf[others] = convergedOf[others] || run.converged.has_value();
    }
    int chart = 0;
    for (auto& [others, byName] : curves) {
      // A technique at one scale only (of another part of the study) has no curve; a group
      // without curves, no table.
      std::vector<ChartSeries> series;
      for (const std::string& name : order) {
        auto it = byName.find(name);
        if (it == byName.end() || it->second.size() < 2) continue;
        std::sort(it->second.begin(), it->second.end());
        series.push_back({name, family[name], it->second});
      }
      if (series.empty()) continue;
      std::set<double> xs;
      for (const ChartSeries& c : series)
        for (const auto& [x, e] : c.points) xs.insert(x);
      const std::string error =
          std::string("visibility RMSE vs ") + (convergedOf[others] ? "converged reference" : "same-sample reference");
      const std::string svg = fmt::format("light-size-{}{}.svg", s.folder, chart++ ? fmt::format("-{}", chart) : "");
      md += fmt::format("\n## {} ({})\n\n{}. Chart: [{}]({})\n\n| technique |", s.name, others, error, svg, svg);
      std::string rule = "|---|";
      for (double x : xs) md += fmt::format(" x{:g} |", x), rule += "---|";
      md += "\n" + rule + "\n";
      for (const ChartSeries& c : series) {
        md += "| " + c.name + " |";
        for (double x : xs) {
          const auto at = std::find_if(c.points.begin(), c.points.end(), [&](auto& p) { return p.first == x; });
          md += at == c.points.end() ? " - |" : fmt::format(" {:.4f} |", at->second);
        }
        md += "\n";
      }
      writeTextFile((root / svg).string(),
                    lineChartSvg("Error against light size: " + s.name + (others.empty() ? "" : ", " + others),
                                 "light scale (x the scene's light)", error, series));
      any = true;
    }
  }
  return any ? md : "";
}

// report/index.html: the headline plot and table, which technique when, the scenes' reports and
// the jobs missing or failed.
std::string indexHtml(const std::string& study, const std::string& renderer, const Headline& h,
                      const std::vector<std::pair<std::string, std::string>>& scenes, const std::string& status,
                      bool lightSize) {
  std::string page = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + escapeMarkup(study) +
                     "</title><style>body{font-family:sans-serif;max-width:1000px;margin:1em auto}"
                     "pre{background:#f4f4f4;padding:.5em;overflow-x:auto}</style></head><body>\n";
  page += "<h1>Study " + escapeMarkup(study) + "</h1>\n<p>" + escapeMarkup(renderer) + "</p>\n";
  page += "<h2>Speed against error, across the scenes</h2>\n<img src=\"headline.svg\" alt=\"headline plot\">\n";
  page += "<pre>" + escapeMarkup(h.text) + "</pre>\n<p><a href=\"stages.md\">Per-stage timings</a>";
  if (lightSize) page += " · <a href=\"light-size.md\">Error against light size</a>";
  page += "</p>\n<h2>Which technique when</h2>\n<pre>" + escapeMarkup(h.summary) + "</pre>\n<h2>Scenes</h2>\n<ul>\n";
  for (const auto& [name, dir] : scenes)
    page += "<li><a href=\"" + escapeMarkup(dir) + "/index.html\">" + escapeMarkup(name) + "</a></li>\n";
  page += "</ul>\n<h2>Jobs</h2>\n<pre>" + escapeMarkup(status) + "</pre>\n</body></html>\n";
  return page;
}

}  // namespace

MergeSummary mergeStudy(const std::string& dir, std::FILE* out) {
  const std::vector<Job> jobs = readPlan(dir);
  std::string study = fs::path(dir).filename().string();
  {
    std::ifstream in(fs::path(dir) / "study.json");
    const json s = json::parse(in, nullptr, false);
    if (s.is_object()) study = s.value("name", study);
  }
  MergeSummary sum;
  sum.jobs = jobs.size();
  std::vector<Row> rows;
  std::string results, status;
  for (const Job& j : jobs) {
    Row r{&j, finishedRow(dir, j)};
    if (r.row.is_null()) {
      ++sum.missing;
      status += fmt::format("missing  {} {} {} ({})\n", j.id, j.kind, j.technique, configLabel(j));
    } else if (!r.ok()) {
      ++sum.failed;
      status += fmt::format("failed   {} {} {} ({}): {}\n", j.id, j.kind, j.technique, configLabel(j),
                            r.row.value("error", "?"));
    } else {
      ++sum.ok;
    }
    if (!r.row.is_null()) results += r.row.dump() + "\n";
    rows.push_back(std::move(r));
  }
  status = fmt::format("{} jobs: {} done, {} failed, {} missing\n", sum.jobs, sum.ok, sum.failed, sum.missing) + status;
  writeTextFile((fs::path(dir) / "results.jsonl").string(), results);
  writeTextFile((fs::path(dir) / "results.csv").string(), resultsCsv(rows));

  // Reports per renderer. A row without one (missing, or failed before it made a GL context)
  // joins every renderer's report.
  auto rendererOf = [](const Row& r) { return r.row.is_null() ? std::string() : r.row.value("renderer", ""); };
  std::vector<std::string> renderers;
  for (const Row& r : rows)
    if (r.job->kind != "converged" && !rendererOf(r).empty() &&
        std::find(renderers.begin(), renderers.end(), rendererOf(r)) == renderers.end())
      renderers.push_back(rendererOf(r));
  if (renderers.empty()) renderers.push_back("no renderer (no job made a GL context)");
  const Axes axes = axesOf(rows);
  for (const std::string& renderer : renderers) {
    const fs::path root =
        renderers.size() == 1 ? fs::path(dir) / "report" : fs::path(dir) / "report" / machineName(renderer);
    std::vector<std::string> sceneOrder;
    std::map<std::string, std::vector<const Row*>> byScene;  // by sceneKey
    for (const Row& r : rows) {
      if (r.job->kind == "converged") continue;
      if (!rendererOf(r).empty() && rendererOf(r) != renderer) continue;
      if (!byScene.count(sceneKey(*r.job))) sceneOrder.push_back(sceneKey(*r.job));
      byScene[sceneKey(*r.job)].push_back(&r);
    }
    std::vector<SceneReport> scenes;
    std::vector<std::pair<std::string, std::string>> links;
    std::set<std::string> folders;
    for (const std::string& scene : sceneOrder) {
      const Job& first = *byScene[scene].front()->job;
      std::string folder = fs::path(first.scene).stem().string();
      for (const auto& v : first.variant) folder += "-" + v;
      folder = fileNameComponent(folder, "scene");
      while (!folders.insert(folder).second) folder += "_";
      const fs::path reportDir = root / folder;
      fs::create_directories(reportDir);
      SceneReport s = sceneReport(byScene[scene], axes, fs::absolute(dir), fs::absolute(reportDir));
      if (s.result.runs.empty()) continue;
      writeReport(s.result, reportDir.string());
      links.emplace_back(s.name, folder);
      s.folder = folder;
      scenes.push_back(std::move(s));
    }
    const Headline h = headlineOf(scenes, axes);
    writeTextFile((root / "headline.md").string(), h.md);
    writeTextFile((root / "headline.txt").string(), h.text);
    writeTextFile((root / "summary.md").string(), h.summary);
    writeTextFile((root / "headline.svg").string(), speedErrorSvg(h.plot));
    writeTextFile((root / "stages.md").string(), stagesMd(scenes));
    const std::string lightSize = lightSizeCurves(scenes, root);
    if (!lightSize.empty()) writeTextFile((root / "light-size.md").string(), lightSize);
    writeTextFile((root / "status.txt").string(), status);
    writeTextFile((root / "index.html").string(), indexHtml(study, renderer, h, links, status, !lightSize.empty()));
    std::fprintf(out, "== %s (%zu scenes)\n%s\nWhich technique when (geometric means over the scenes):\n%s\n",
                 renderer.c_str(), scenes.size(), h.text.c_str(), h.summary.c_str());
    sum.reports.push_back(root.string());
  }
  std::fprintf(out, "%s", status.c_str());
  return sum;
}

}  // namespace penumbra::study
