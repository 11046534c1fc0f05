#include "pipeline/report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra {
namespace {

// Distinct on white and for common colour-vision deficiencies first (Okabe-Ito), then more.
constexpr const char* kPalette[] = {"#0072B2", "#E69F00", "#009E73", "#D55E00", "#CC79A7", "#56B4E9",
                                    "#000000", "#F0E442", "#8C564B", "#7F7F7F", "#1F3A93", "#BCBD22",
                                    "#17BECF", "#9467BD", "#2CA02C", "#FF7F0E"};

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (auto& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

std::string runLabel(const CompareResult& r, const CompareRun& run) {
  const std::string& p = r.presets[run.preset].label;
  return run.technique + (run.reference ? " (ref)" : "") + (p.empty() ? "" : " @ " + p);
}

std::string stagesText(const CompareRun& run) {
  std::vector<std::string> parts;
  for (auto& [k, v] : run.stages) parts.push_back(fmt::format("{} {:.1f}", k, v.median));
  return join(parts, ", ");
}

// The harness's stages (readbacks, uploads) of a run, apart from the technique's.
std::string harnessText(const CompareRun& run) {
  std::vector<std::string> parts;
  for (auto& [k, v] : run.harnessStages) parts.push_back(fmt::format("{} {:.1f}", k, v.median));
  return join(parts, ", ");
}

// A count in 4 significant digits with k/M/G (pipeline statistics).
std::string countText(std::uint64_t n) {
  if (n < 10000) return std::to_string(n);
  const char* unit[] = {"k", "M", "G", "T"};
  double v = double(n);
  int u = -1;
  while (v >= 1000.0 && u < 3) v /= 1000.0, ++u;
  return fmt::format("{:.4g}{}", v, unit[u]);
}

// Each stage's counts: "stage: fragment=.. geometry=.. compute=.. primitives=..; ..." (CSV).
std::string countsText(const CompareRun& run) {
  std::vector<std::string> parts;
  for (auto& [k, c] : run.counts) {
    std::vector<std::string> f;
    for (auto& [name, v] : c.fields()) f.push_back(fmt::format("{}={}", name, v));
    parts.push_back(k + ": " + join(f, " "));
  }
  return join(parts, "; ");
}

// Technique names in first-appearance order (colours follow it).
std::vector<std::string> techniqueOrder(const CompareResult& r, const std::vector<std::size_t>& runs) {
  std::vector<std::string> names;
  for (auto i : runs)
    if (std::find(names.begin(), names.end(), r.runs[i].technique) == names.end()) names.push_back(r.runs[i].technique);
  return names;
}

// Decade ticks of [lo, hi] (log10 values), with 2 and 5 (or every digit) in between when the
// range is short.
std::vector<double> logTicks(double lo, double hi) {
  std::vector<double> ticks;
  const std::vector<double> mantissas = hi - lo < 1.2   ? std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9}
                                        : hi - lo < 2.5 ? std::vector<double>{1, 2, 5}
                                                        : std::vector<double>{1};
  for (int e = int(std::floor(lo)); e <= int(std::ceil(hi)); ++e)
    for (double m : mantissas) {
      double t = e + std::log10(m);
      if (t >= lo - 1e-9 && t <= hi + 1e-9) ticks.push_back(t);
    }
  return ticks;
}

std::string tickLabel(double log10v) {
  double v = std::pow(10.0, log10v);
  if (v >= 1000) return fmt::format("{:.0f}", v);
  if (v >= 1) return fmt::format("{:g}", std::round(v * 100) / 100);
  return fmt::format("{:.2g}", v);
}

}  // namespace

std::vector<std::size_t> paretoFront(const std::vector<std::pair<double, double>>& pts) {
  std::vector<std::size_t> order(pts.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return pts[a].first != pts[b].first ? pts[a].first < pts[b].first : pts[a].second < pts[b].second;
  });
  // A point joins the front when it is more accurate than everything at least as fast by more
  // than kTie (relative): dcs equals the same-sample reference up to float rounding, and being
  // 1e-9 "better" must not put the slower of two equal results on the front.
  constexpr double kTie = 1e-3;
  std::vector<std::size_t> front;
  double best = INFINITY;
  for (std::size_t i : order)
    if (pts[i].second < best * (1.0 - kTie)) {
      front.push_back(i);
      best = pts[i].second;
    }
  return front;
}

std::vector<std::size_t> plottedRuns(const CompareResult& r) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < r.runs.size(); ++i) {
    const CompareRun& run = r.runs[i];
    if (run.failed || (run.reference && !run.converged)) continue;
    if (!(run.total.median > 0.0) || !std::isfinite(run.plotError())) continue;
    out.push_back(i);
  }
  return out;
}

std::string speedErrorSvg(const CompareResult& r) {
  const auto runs = plottedRuns(r);
  const auto names = techniqueOrder(r, runs);
  const double left = 70, right = 190, top = 30, bottom = 50, W = 760;
  const double H = std::max(460.0, top + 15.0 * double(names.size()) + 40.0 + bottom);  // room for the legend
  const double pw = W - left - right, ph = H - top - bottom;
  // Exact techniques (dcs against the same-sample reference: float rounding, ~1e-8) would
  // stretch the axis over decades of nothing: errors below kExact sit on a floor labelled so.
  constexpr double kExact = 1e-4;
  bool anyExact = false;
  for (auto i : runs) anyExact |= r.runs[i].plotError() < kExact;
  auto errorOf = [&](std::size_t i) { return std::max(r.runs[i].plotError(), kExact); };
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (auto i : runs) {
    x0 = std::min(x0, std::log10(r.runs[i].total.median)), x1 = std::max(x1, std::log10(r.runs[i].total.median));
    y0 = std::min(y0, std::log10(errorOf(i))), y1 = std::max(y1, std::log10(errorOf(i)));
  }
  if (runs.empty()) x0 = 0, x1 = 1, y0 = -3, y1 = 0;
  auto pad = [](double& lo, double& hi) {
    if (hi - lo < 0.5) {
      double mid = 0.5 * (lo + hi);
      lo = mid - 0.25, hi = mid + 0.25;
    }
    double p = 0.06 * (hi - lo);
    lo -= p, hi += p;
  };
  pad(x0, x1), pad(y0, y1);
  auto X = [&](double ms) { return left + (std::log10(ms) - x0) / (x1 - x0) * pw; };
  auto Y = [&](double e) { return top + (1.0 - (std::log10(e) - y0) / (y1 - y0)) * ph; };
  const std::string errorName = r.hasConverged() ? "visibility RMSE vs converged reference" : "visibility RMSE vs same-sample reference";

  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"12\" role=\"img\" aria-label=\"speed against error\">\n"
      "<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
      W, H);
  s += fmt::format("<text x=\"{}\" y=\"18\" font-size=\"14\">Speed against error: {}</text>\n", left,
                   escape(r.info.value("sceneName", std::string("scene"))));
  // Grid and ticks.
  for (double t : logTicks(x0, x1)) {
    double x = left + (t - x0) / (x1 - x0) * pw;
    s += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>"
                     "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4}</text>\n",
                     x, top, top + ph, top + ph + 16, tickLabel(t));
  }
  for (double t : logTicks(y0, y1)) {
    double y = top + (1.0 - (t - y0) / (y1 - y0)) * ph;
    bool exact = anyExact && std::abs(t - std::log10(kExact)) < 1e-9;
    s += fmt::format("<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
                     "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>\n",
                     left, y, left + pw, left - 6, y + 4, exact ? "&#8804;1e-4" : tickLabel(t));
  }
  s += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333\"/>\n", left, top, pw, ph);
  s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">median ms per frame (log)</text>\n", left + pw / 2, H - 10);
  s += fmt::format("<text transform=\"translate(16 {}) rotate(-90)\" text-anchor=\"middle\">{} (log)</text>\n", top + ph / 2,
                   errorName);

  // Pareto front (dashed steps), then one curve and the points per technique.
  std::vector<std::pair<double, double>> pts;
  for (auto i : runs) pts.emplace_back(r.runs[i].total.median, errorOf(i));
  auto front = paretoFront(pts);
  if (front.size() > 1) {
    std::string path;
    for (std::size_t k = 0; k < front.size(); ++k) {
      double x = X(pts[front[k]].first), y = Y(pts[front[k]].second);
      if (k == 0) path += fmt::format("M{:.1f},{:.1f}", x, y);
      else path += fmt::format(" H{:.1f} V{:.1f}", x, y);
    }
    s += "<path class=\"pareto\" d=\"" + path + "\" fill=\"none\" stroke=\"#888\" stroke-dasharray=\"5,4\"/>\n";
  }
  for (std::size_t t = 0; t < names.size(); ++t) {
    // Colours cycle; past the palette the markers turn from circles to squares.
    const char* colour = kPalette[t % std::size(kPalette)];
    const bool square = (t / std::size(kPalette)) % 2 == 1;
    auto marker = [square](double x, double y, double r, const std::string& attrs, const std::string& body) {
      if (square)
        return fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" {}>{}</rect>\n", x - r, y - r,
                           2 * r, 2 * r, attrs, body);
      return fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\" {}>{}</circle>\n", x, y, r, attrs, body);
    };
    std::vector<std::size_t> mine;
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (r.runs[runs[k]].technique == names[t]) mine.push_back(k);
    std::sort(mine.begin(), mine.end(), [&](auto a, auto b) { return pts[a].first < pts[b].first; });
    if (mine.size() > 1) {
      std::string path;
      for (std::size_t k = 0; k < mine.size(); ++k)
        path += fmt::format("{}{:.1f},{:.1f}", k ? " L" : "M", X(pts[mine[k]].first), Y(pts[mine[k]].second));
      s += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>\n", path, colour);
    }
    for (auto k : mine) {
      const CompareRun& run = r.runs[runs[k]];
      bool onFront = std::find(front.begin(), front.end(), k) != front.end();
      s += marker(X(pts[k].first), Y(pts[k].second), onFront ? 5 : 4,
                  fmt::format("class=\"point\" fill=\"{}\" stroke=\"{}\" stroke-width=\"{}\"", colour,
                              onFront ? "#000" : "white", onFront ? 1.5 : 1),
                  fmt::format("<title>{}: {:.2f} ms, RMSE {:.4g}{}</title>", escape(runLabel(r, run)), run.total.median,
                              run.plotError(), onFront ? " (Pareto front)" : ""));
    }
    double ly = top + 8 + 15.0 * double(t);
    s += marker(left + pw + 14, ly, 4, fmt::format("fill=\"{}\"", colour), "") +
         fmt::format("<text x=\"{}\" y=\"{:.1f}\">{}</text>\n", left + pw + 24, ly + 4, escape(names[t]));
  }
  double ly = top + 8 + 15.0 * double(names.size()) + 6;
  s += fmt::format("<line x1=\"{}\" y1=\"{:.1f}\" x2=\"{}\" y2=\"{:.1f}\" stroke=\"#888\" stroke-dasharray=\"5,4\"/>"
                   "<text x=\"{}\" y=\"{:.1f}\">Pareto front</text>\n",
                   left + pw + 8, ly, left + pw + 20, ly, left + pw + 24, ly + 4);
  s += "</svg>\n";
  return s;
}

std::string reportTable(const CompareResult& r) {
  const bool conv = r.hasConverged(), temporal = r.hasTemporal();
  const bool counted = std::any_of(r.runs.begin(), r.runs.end(), [](const CompareRun& x) { return !x.counts.empty(); });
  std::string t;
  // Totals are the technique's time; the harness's readbacks and uploads are the "harness" column.
  if (!counted && r.info.contains("pipelineStatistics"))
    t += "pipeline statistics: " + r.info["pipelineStatistics"].get<std::string>() + "\n";
  t += fmt::format("{:<32} {:>9} {:>17} {:>9} {:>8} {:>9} {:>8} {:>9} {:>10}", "technique", "total ms",
                   "(min-max)", "harness", "MiB", "vis RMSE", "vis max", "img RMSE", "misclass");
  if (conv) t += fmt::format(" {:>10}", "conv RMSE");
  if (temporal) t += fmt::format(" {:>9}", "flicker");
  if (counted) t += fmt::format(" {:>9} {:>9} {:>9} {:>9}", "fragments", "geometry", "compute", "prims");
  t += "  stages ms\n";
  for (auto& run : r.runs) {
    if (run.failed) {
      t += fmt::format("{:<32} FAILED: {}\n", runLabel(r, run), run.failure);
      continue;
    }
    t += fmt::format("{:<32} {:>9.1f} {:>17} {:>9.1f} {:>8.1f}", runLabel(r, run), run.total.median,
                     fmt::format("({:.1f}-{:.1f})", run.total.min, run.total.max), run.harness.median,
                     double(run.memoryBytes) / 1048576.0);
    if (run.reference && !run.converged) t += fmt::format(" {:>9} {:>8} {:>9} {:>10}", "-", "-", "-", "-");
    else if (run.reference) t += fmt::format(" {:>9} {:>8} {:>9} {:>10}", "0", "0", "0", "0");
    else
      t += fmt::format(" {:>9.4f} {:>8.4f} {:>9.4g} {:>10}", run.errors.visibility.rmse, run.errors.visibility.maxAbs,
                       run.errors.shaded.rmse, run.errors.misclassifiedPixels);
    if (conv) t += run.converged ? fmt::format(" {:>10.4f}", run.converged->visibility.rmse) : fmt::format(" {:>10}", "-");
    if (temporal) t += run.flicker >= 0.0 ? fmt::format(" {:>9.4f}", run.flicker) : fmt::format(" {:>9}", "-");
    if (counted) {
      const PipelineCounts c = totalCounts(run);
      t += fmt::format(" {:>9} {:>9} {:>9} {:>9}", countText(c.fragmentInvocations), countText(c.geometryInvocations),
                       countText(c.computeInvocations), countText(c.primitivesSubmitted));
    }
    t += "  " + stagesText(run);
    if (!run.harnessStages.empty()) t += " | harness: " + harnessText(run);
    t += "\n";
  }
  return t;
}

std::string reportCsv(const CompareResult& r) {
  std::string c =
      "scene,technique,reference,preset,params,samples,width,height,shading,total_ms_median,total_ms_min,total_ms_max,"
      "prepare_ms,stages_ms,memory_bytes,vis_rmse,vis_mean,vis_max,vis_rmse_outside_band,misclassified_pixels,"
      "sample_agreement,img_rmse,img_mean,img_max,conv_vis_rmse,conv_vis_mean,conv_vis_max,conv_img_rmse,flicker,"
      "reference_motion,mean_frame_rmse,harness_ms_median,harness_stages_ms,primitives,vertex_invocations,"
      "geometry_invocations,rasterized_primitives,fragment_invocations,compute_invocations,pipeline_statistics,"
      "image,status,error\n";
  const std::string scene = r.info.value("sceneName", std::string());
  auto num = [](double v) { return fmt::format("{:.6g}", v); };
  for (auto& run : r.runs) {
    const ComparePreset& p = r.presets[run.preset];
    if (run.failed) {
      // The run's identity, empty numbers (never measured), then why it failed.
      std::vector<std::string> f = {csvField(scene), csvField(run.technique), run.reference ? "1" : "0", csvField(p.label),
                                    csvField(join(run.params, " ")), std::to_string(p.samples), std::to_string(p.width),
                                    std::to_string(p.height), run.shading};
      f.insert(f.end(), 23 + 9, "");
      f.push_back("failed");
      f.push_back(csvField(run.failure));
      c += join(f, ",") + "\n";
      continue;
    }
    std::vector<std::string> stages;
    for (auto& [k, v] : run.stages) stages.push_back(k + "=" + fmt::format("{:.3f}", v.median));
    const TechniqueErrors& e = run.errors;
    std::vector<std::string> f = {csvField(scene), csvField(run.technique), run.reference ? "1" : "0", csvField(p.label),
                                  csvField(join(run.params, " ")), std::to_string(p.samples), std::to_string(p.width),
                                  std::to_string(p.height), run.shading, num(run.total.median), num(run.total.min),
                                  num(run.total.max), num(run.prepareMs), csvField(join(stages, ";")),
                                  std::to_string(run.memoryBytes), num(e.visibility.rmse), num(e.visibility.meanAbs),
                                  num(e.visibility.maxAbs), num(e.visibilityOutsideBand.rmse),
                                  std::to_string(e.misclassifiedPixels), e.sampleAgreement >= 0 ? num(e.sampleAgreement) : "",
                                  num(e.shaded.rmse), num(e.shaded.meanAbs), num(e.shaded.maxAbs)};
    if (run.converged) {
      const TechniqueErrors& ce = *run.converged;
      for (double v : {ce.visibility.rmse, ce.visibility.meanAbs, ce.visibility.maxAbs, ce.shaded.rmse}) f.push_back(num(v));
    } else {
      f.insert(f.end(), 4, "");
    }
    for (double v : {run.flicker, run.referenceMotion, run.meanFrameRmse}) f.push_back(v >= 0.0 ? num(v) : "");
    std::vector<std::string> harness;
    for (auto& [k, v] : run.harnessStages) harness.push_back(k + "=" + fmt::format("{:.3f}", v.median));
    f.push_back(num(run.harness.median));
    f.push_back(csvField(join(harness, ";")));
    if (run.counts.empty()) {
      f.insert(f.end(), 7, "");  // not counted: empty, never 0 (report.json's info says why)
    } else {
      for (auto& [k, v] : totalCounts(run).fields()) f.push_back(std::to_string(v));
      f.push_back(csvField(countsText(run)));
    }
    f.push_back(csvField(run.image));
    f.push_back("ok");
    f.push_back("");
    c += join(f, ",") + "\n";
  }
  return c;
}

std::string reportHtml(const CompareResult& r) {
  const auto& info = r.info;
  const bool conv = r.hasConverged(), temporal = r.hasTemporal();
  std::string h = R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>penumbra compare: )" + escape(info.value("sceneName", std::string())) + R"(</title>
<style>
body { font-family: system-ui, sans-serif; margin: 1.5em; color: #222; max-width: 1400px; }
h1 { font-size: 1.4em; } h2 { font-size: 1.15em; margin-top: 1.6em; }
.meta { color: #555; }
table { border-collapse: collapse; font-size: 0.85em; }
th, td { border-bottom: 1px solid #ddd; padding: 3px 8px; text-align: right; vertical-align: top; white-space: nowrap; }
th { background: #f4f4f4; position: sticky; top: 0; }
td.l, th.l { text-align: left; }
td.st { white-space: normal; min-width: 300px; font-size: 0.9em; }
tr.ref td { color: #555; font-style: italic; }
tr.failed td { color: #b00020; background: #fff0f0; }
tr.front td:first-child { font-weight: bold; }
.gallery { display: flex; flex-wrap: wrap; gap: 12px; }
figure { margin: 0; border: 1px solid #ddd; padding: 6px; background: #fafafa; }
figure img { display: block; image-rendering: pixelated; }
figcaption { font-size: 0.8em; max-width: 400px; }
.pair { display: flex; gap: 4px; }
.insets { display: flex; flex-wrap: wrap; gap: 8px; align-items: flex-start; }
img.missing { outline: 3px solid red; min-width: 64px; min-height: 64px; }
.note { font-size: 0.85em; color: #555; max-width: 900px; }
</style></head>
<body>
)";
  h += "<h1>penumbra compare: " + escape(info.value("sceneName", std::string())) + "</h1>\n";
  h += fmt::format("<p class=\"meta\">scene <code>{}</code> ({} triangles, {} lights) &middot; {}x{} &middot; {} samples, {} / {} "
                   "(seed {}) &middot; shading {} &middot; renderer {} ({}) &middot; timing: median of {} frames after {} "
                   "warm-up (glFinish + steady clock) &middot; {}</p>\n",
                   escape(info.value("scene", std::string())), info.value("triangles", 0), info.value("lights", 0),
                   info.value("width", 0), info.value("height", 0), info.value("samples", 0),
                   escape(info.value("strategy", std::string())), escape(info.value("pattern", std::string())),
                   info.value("seed", 0u), escape(info.value("shading", std::string())),
                   escape(info.value("renderer", std::string())), escape(info.value("glVersion", std::string())),
                   info.value("timingFrames", 0), info.value("warmupFrames", 0), escape(info.value("date", std::string())));
  h += "<p class=\"meta\">total: the technique's stages (G-buffer, visibility, shading); the harness's readbacks and "
       "uploads apart &middot; pipeline statistics: " + escape(info.value("pipelineStatistics", std::string("-"))) + "</p>\n";
  if (!info.value("params", std::vector<std::string>{}).empty())
    h += "<p class=\"meta\">parameters: <code>" + escape(join(info["params"].get<std::vector<std::string>>(), " ")) + "</code></p>\n";
  if (r.presets.size() > 1) {
    std::vector<std::string> labels;
    for (auto& p : r.presets) labels.push_back(p.label);
    h += "<p class=\"meta\">presets (sweep): " + escape(join(labels, " | ")) + "</p>\n";
  }

  h += "<h2>Speed against error</h2>\n<div class=\"plot\">\n" + speedErrorSvg(r) + "</div>\n";
  h += std::string("<p class=\"note\">Each point is one technique at one preset: the median time per frame against the "
                   "visibility RMSE (all lights, surface pixels) against the ") +
       (conv ? "converged reference (raytrace-converged, 1024 stratified samples per pixel)"
             : "ray-traced reference with the same light samples") +
       ". Points on the dashed Pareto front (outlined) are faster than every more accurate point. Hover a point for its "
       "numbers.</p>\n";

  // The table.
  const auto plotted = plottedRuns(r);
  std::vector<std::pair<double, double>> pts;
  for (auto i : plotted) pts.emplace_back(r.runs[i].total.median, r.runs[i].plotError());
  std::vector<std::size_t> frontRuns;
  for (auto k : paretoFront(pts)) frontRuns.push_back(plotted[k]);
  h += "<h2>Table</h2>\n<table>\n<tr><th class=\"l\">technique</th><th class=\"l\">preset</th><th class=\"l\">parameters</th>"
       "<th>samples</th><th>total ms<br>median</th><th>min&ndash;max</th><th class=\"l\">stages ms (median)</th><th>prepare ms</th>"
       "<th>memory MiB</th><th>vis RMSE</th><th>vis mean</th><th>vis max</th><th>misclassified px</th>"
       "<th>img RMSE</th><th>img mean</th><th>img max</th>";
  if (conv) h += "<th>vis RMSE vs converged</th><th>img RMSE vs converged</th>";
  if (temporal) h += "<th>flicker</th><th>reference motion</th><th>mean frame RMSE</th>";
  h += "</tr>\n";
  for (std::size_t i = 0; i < r.runs.size(); ++i) {
    const CompareRun& run = r.runs[i];
    const ComparePreset& p = r.presets[run.preset];
    bool front = std::find(frontRuns.begin(), frontRuns.end(), i) != frontRuns.end();
    std::vector<std::string> stageList;
    for (auto& [k, v] : run.stages) stageList.push_back(fmt::format("{}&nbsp;{:.2f}", escape(k), v.median));
    std::string stages = join(stageList, " &middot; ");
    if (!run.harnessStages.empty()) {  // the harness's readbacks and uploads, not in the total
      std::vector<std::string> harness;
      for (auto& [k, v] : run.harnessStages) harness.push_back(fmt::format("{}&nbsp;{:.2f}", escape(k), v.median));
      stages += fmt::format("<br><i>harness {:.2f}: {}</i>", run.harness.median, join(harness, " &middot; "));
    }
    if (!run.counts.empty()) {
      const PipelineCounts pc = totalCounts(run);
      stages += fmt::format("<br>fragments {} &middot; geometry {} &middot; compute {} &middot; primitives {}",
                            countText(pc.fragmentInvocations), countText(pc.geometryInvocations),
                            countText(pc.computeInvocations), countText(pc.primitivesSubmitted));
    }
    if (run.failed) {
      const int rest = 12 + (conv ? 2 : 0) + (temporal ? 3 : 0);
      h += fmt::format("<tr class=\"failed\"><td class=\"l\">{}</td><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{}</td>"
                       "<td class=\"l st\" colspan=\"{}\"><b>failed:</b> {}</td></tr>\n",
                       escape(run.technique), escape(p.label), escape(join(run.params, " ")), p.samples, rest,
                       escape(run.failure));
      continue;
    }
    h += fmt::format("<tr class=\"{}\"><td class=\"l\">{}{}</td><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{}</td>"
                     "<td>{:.2f}</td><td>{:.2f}&ndash;{:.2f}</td><td class=\"l st\">{}</td><td>{:.1f}</td><td>{:.2f}</td>",
                     run.reference ? "ref" : (front ? "front" : ""), escape(run.technique), run.reference ? " (reference)" : "",
                     escape(p.label), escape(join(run.params, " ")), p.samples, run.total.median, run.total.min,
                     run.total.max, stages, run.prepareMs, double(run.memoryBytes) / 1048576.0);
    const TechniqueErrors& e = run.errors;
    if (run.reference) h += "<td>-</td><td>-</td><td>-</td><td>-</td><td>-</td><td>-</td><td>-</td>";
    else
      h += fmt::format("<td>{:.4f}</td><td>{:.4f}</td><td>{:.4f}</td><td>{}</td><td>{:.4g}</td><td>{:.4g}</td><td>{:.4g}</td>",
                       e.visibility.rmse, e.visibility.meanAbs, e.visibility.maxAbs, e.misclassifiedPixels, e.shaded.rmse,
                       e.shaded.meanAbs, e.shaded.maxAbs);
    if (conv)
      h += run.converged ? fmt::format("<td>{:.4f}</td><td>{:.4g}</td>", run.converged->visibility.rmse, run.converged->shaded.rmse)
                         : "<td>-</td><td>-</td>";
    if (temporal)
      h += run.flicker >= 0.0
               ? fmt::format("<td>{:.4f}</td><td>{:.4f}</td><td>{:.4f}</td>", run.flicker, run.referenceMotion, run.meanFrameRmse)
               : "<td>-</td><td>-</td><td>-</td>";
    h += "</tr>\n";
  }
  h += "</table>\n<p class=\"note\">vis: the visibility buffers of all lights (eq. 2), img: the shaded linear image, both "
       "against the same-sample reference over pixels with a surface; misclassified: pixels outside the 1-pixel edge band "
       "whose visibility differs by more than half a sample. Bold: on the Pareto front.";
  if (temporal)
    h += " flicker: RMS over frames and pixels of the frame-to-frame change in visibility minus the reference's change (what "
         "moves that the reference does not); reference motion: the reference's own RMS change.";
  h += "</p>\n";

  // Images, one gallery per preset.
  h += "<h2>Images</h2>\n<p class=\"note\">Left: the shaded image; right: the visibility error of the first light against the "
       "" + std::string(conv ? "converged" : "same-sample") + " reference (heat map, black 0 to yellow 0.25 or more).</p>\n";
  for (std::size_t p = 0; p < r.presets.size(); ++p) {
    h += fmt::format("<details{}><summary>{}</summary>\n<div class=\"gallery\">\n", p == 0 ? " open" : "",
                     r.presets[p].label.empty() ? "all techniques" : escape(r.presets[p].label));
    // Small renders are shown enlarged (pixelated), at least 192 px wide.
    const int zoom = std::max(1, 192 / std::max(1, r.presets[p].width));
    const std::string size = fmt::format(" width=\"{}\" height=\"{}\"", r.presets[p].width * zoom, r.presets[p].height * zoom);
    for (auto& run : r.runs) {
      if (run.preset != p || run.image.empty()) continue;
      h += "<figure><div class=\"pair\"><img src=\"" + escape(run.image) + "\"" + size + " alt=\"" + escape(run.technique) + "\">";
      if (!run.heat.empty())
        h += "<img src=\"" + escape(run.heat) + "\"" + size + " alt=\"" + escape(run.technique) + " error\">";
      if (!run.unshadowedMask.empty())
        h += "<img src=\"" + escape(run.unshadowedMask) + "\"" + size + " alt=\"" + escape(run.technique) +
             " pixels left unshadowed\">";
      h += "</div><figcaption><b>" + escape(run.technique) + (run.reference ? " (reference)" : "") + "</b> " +
           fmt::format("{:.1f} ms", run.total.median);
      if (!run.reference) h += fmt::format(", vis RMSE {:.4f}", run.errors.visibility.rmse);
      if (run.errors.unshadowedPixels > 0)
        h += fmt::format("; {} pixels left unshadowed (outside its maps, white in the third image), vis RMSE {:.4f} "
                         "without them",
                         run.errors.unshadowedPixels, run.errors.visibilityExceptUnshadowed.rmse);
      if (run.converged) h += fmt::format(", vs converged {:.4f}", run.converged->visibility.rmse);
      h += "</figcaption></figure>\n";
    }
    h += "</div></details>\n";
  }

  if (!r.insets.empty()) {
    h += "<h2>Insets</h2>\n";
    for (std::size_t k = 0; k < r.insets.size(); ++k) {
      const Inset& in = r.insets[k];
      h += fmt::format("<h3>region {}: x {}, y {}, {}x{} px ({})</h3>\n<div class=\"insets\">\n", k + 1, in.x, in.y, in.w, in.h,
                       r.insetSource == "given" ? "given with --inset" : "most penumbra pixels of the reference");
      for (auto& run : r.runs) {
        if (run.preset != 0 || k >= run.insetImages.size()) continue;
        h += "<figure><img src=\"" + escape(run.insetImages[k]) + "\" alt=\"" + escape(run.technique) + " inset\"><figcaption>" +
             escape(run.technique) + "</figcaption></figure>\n";
      }
      h += "</div>\n";
    }
  }
  h += "<h2>Files</h2>\n<p><a href=\"report.json\">report.json</a> &middot; <a href=\"report.csv\">report.csv</a> &middot; "
       "<a href=\"table.txt\">table.txt</a> &middot; <a href=\"plot.svg\">plot.svg</a> &middot; <code>&lt;technique&gt;.exr</code>: "
       "float colour and per-light visibility layers</p>\n";
  // Marks images that failed to load (and says how many loaded, for the headless check).
  h += R"(<script>
window.addEventListener('load', function () {
  var imgs = Array.prototype.slice.call(document.images), ok = 0;
  imgs.forEach(function (i) {
    if (i.complete && i.naturalWidth > 0) { ok++; } else { i.classList.add('missing'); i.title = 'missing: ' + i.getAttribute('src'); }
  });
  document.body.setAttribute('data-images', ok + '/' + imgs.length);
  document.body.setAttribute('data-plot-points', document.querySelectorAll('svg .point').length);
});
</script>
</body></html>
)";
  return h;
}

void writeReport(const CompareResult& r, const std::string& dir) {
  namespace fs = std::filesystem;
  auto write = [&](const std::string& name, const std::string& text) {
    fs::path p = fs::path(dir) / name;
    std::ofstream out(p);
    out << text;
    if (!out) throw Error(p.string(), "cannot write");
  };
  write("report.json", r.json().dump(2) + "\n");
  write("report.csv", reportCsv(r));
  write("table.txt", reportTable(r));
  write("plot.svg", speedErrorSvg(r));
  write("index.html", reportHtml(r));
}

}  // namespace penumbra
