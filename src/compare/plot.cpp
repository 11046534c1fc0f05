#include "compare/plot.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

namespace penumbra {
namespace {

// Okabe and Ito's colour-blind-safe palette, one colour a family.
const char* familyColour(TechniqueFamily f) {
  switch (f) {
    case TechniqueFamily::ExactPerSample:
      return "#0072B2";  // blue
    case TechniqueFamily::MultiView:
      return "#009E73";  // bluish green
    case TechniqueFamily::SingleMap:
      return "#E69F00";  // orange
    case TechniqueFamily::Denoised:
      return "#CC79A7";  // reddish purple
    case TechniqueFamily::Hard:
      return "#000000";  // black
  }
  return "#777777";
}

// The family colour mixed with white by `t` (the lighter shade of a variant).
std::string lighter(const char* hex, double t) {
  unsigned rgb = 0;
  std::sscanf(hex + 1, "%6x", &rgb);
  auto mix = [&](unsigned c) { return unsigned(std::lround(double(c) + (255.0 - double(c)) * t)); };
  return fmt::format("#{:02X}{:02X}{:02X}", mix((rgb >> 16) & 255u), mix((rgb >> 8) & 255u), mix(rgb & 255u));
}

// A variant's look within its family: one of six shapes, full or lighter shade.
enum class Shape { Circle, Square, Up, Diamond, Down, Plus };
struct Look {
  std::string colour;
  Shape shape;
};
Look lookOf(TechniqueFamily f, int variant) {
  const Shape shape = Shape(variant % 6);
  return {(variant / 6) % 2 ? lighter(familyColour(f), 0.45) : std::string(familyColour(f)), shape};
}

// A marker centred at (x, y), radius r, with the given attributes and content (a <title>).
std::string marker(Shape shape, double x, double y, double r, const std::string& attrs, const std::string& body) {
  auto poly = [&](std::initializer_list<std::pair<double, double>> pts) {
    std::string d;
    for (auto [px, py] : pts) d += fmt::format("{}{:.1f},{:.1f}", d.empty() ? "M" : " L", x + px * r, y + py * r);
    return fmt::format("<path d=\"{} Z\" {}>{}</path>\n", d, attrs, body);
  };
  switch (shape) {
    case Shape::Circle:
      return fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\" {}>{}</circle>\n", x, y, r, attrs, body);
    case Shape::Square:
      return fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" {}>{}</rect>\n",
                         x - 0.9 * r, y - 0.9 * r, 1.8 * r, 1.8 * r, attrs, body);
    case Shape::Up:
      return poly({{0, -1.25}, {1.1, 0.75}, {-1.1, 0.75}});
    case Shape::Down:
      return poly({{0, 1.25}, {1.1, -0.75}, {-1.1, -0.75}});
    case Shape::Diamond:
      return poly({{0, -1.3}, {1.3, 0}, {0, 1.3}, {-1.3, 0}});
    case Shape::Plus:
      return poly({{-0.4, -1.2},
                   {0.4, -1.2},
                   {0.4, -0.4},
                   {1.2, -0.4},
                   {1.2, 0.4},
                   {0.4, 0.4},
                   {0.4, 1.2},
                   {-0.4, 1.2},
                   {-0.4, 0.4},
                   {-1.2, 0.4},
                   {-1.2, -0.4},
                   {-0.4, -0.4}});
  }
  return {};
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

// The preset part of a point's label: "N=16" for samples=16, the rest as given.
std::string presetShort(const std::string& label) {
  std::string s = label;
  for (std::size_t at = s.find("samples="); at != std::string::npos; at = s.find("samples=", at))
    s.replace(at, 8, "N=");
  return s;
}

// Axis-aligned boxes for the label placement.
struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& b) const { return x0 < b.x1 && b.x0 < x1 && y0 < b.y1 && b.y0 < y1; }
};

// Label font: 10 px sans-serif; widths are estimated on the generous side (6.2 px a character)
// so that the browser's real text stays inside the box the placement reserved.
constexpr double kLabelFont = 10.0, kCharWidth = 6.2;

}  // namespace

std::string escapeMarkup(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string runLabel(const CompareResult& r, const CompareRun& run) {
  const std::string& p = r.presets[run.preset].label;
  return run.technique + (run.reference ? " (ref)" : "") + (p.empty() ? "" : " @ " + p);
}

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

std::vector<std::size_t> plottedRuns(const CompareResult& r, ErrorAxis axis) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < r.runs.size(); ++i) {
    const CompareRun& run = r.runs[i];
    if (run.failed || (run.reference && !run.converged)) continue;
    const double e = run.errorOn(axis);
    if (!(run.total.median > 0.0) || !std::isfinite(e) || e < 0.0) continue;
    out.push_back(i);
  }
  return out;
}

std::vector<std::size_t> paretoRuns(const CompareResult& r, ErrorAxis axis) {
  const auto runs = plottedRuns(r, axis);
  std::vector<std::pair<double, double>> pts;
  for (auto i : runs) pts.emplace_back(r.runs[i].total.median, std::max(r.runs[i].errorOn(axis), kExactErrorFloor));
  std::vector<std::size_t> front;
  for (auto k : paretoFront(pts)) front.push_back(runs[k]);
  return front;
}

std::string errorAxisName(const CompareResult& r, ErrorAxis axis) {
  const std::string against = r.hasConverged() ? "converged reference" : "same-sample reference";
  switch (axis) {
    case ErrorAxis::Visibility:
      return "visibility RMSE vs " + against;
    case ErrorAxis::Shaded:
      return "shaded-image RMSE vs " + against;
    case ErrorAxis::Flip:
      return "mean HDR-FLIP vs " + against;
  }
  return {};
}

std::string speedErrorSvg(const CompareResult& r, ErrorAxis axis) {
  const auto runs = plottedRuns(r, axis);
  // Techniques grouped by family (in the families' order), each family's in first-appearance order.
  std::vector<std::string> names;
  std::map<std::string, TechniqueFamily> familyOf;
  for (auto i : runs) familyOf.emplace(r.runs[i].technique, r.runs[i].family);
  for (TechniqueFamily f : kTechniqueFamilies)
    for (auto i : runs)
      if (r.runs[i].family == f && std::find(names.begin(), names.end(), r.runs[i].technique) == names.end())
        names.push_back(r.runs[i].technique);
  std::map<std::string, Look> looks;
  {
    std::map<TechniqueFamily, int> variants;
    for (auto& n : names) looks.emplace(n, lookOf(familyOf[n], variants[familyOf[n]]++));
  }
  int familiesShown = 0;
  for (TechniqueFamily f : kTechniqueFamilies)
    familiesShown += std::any_of(names.begin(), names.end(), [&](auto& n) { return familyOf[n] == f; });

  const double left = 70, right = 200, top = 30, bottom = 50, W = 800, line = 14;
  const double legendHeight = line * double(names.size() + std::size_t(familiesShown)) + 30.0;
  const double H = std::max(480.0, top + legendHeight + bottom);
  const double pw = W - left - right, ph = H - top - bottom;
  constexpr double kExact = kExactErrorFloor;
  bool anyExact = false;
  for (auto i : runs) anyExact |= r.runs[i].errorOn(axis) < kExact;
  auto errorOf = [&](std::size_t i) { return std::max(r.runs[i].errorOn(axis), kExact); };
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (auto i : runs) {
    x0 = std::min(x0, std::log10(r.runs[i].total.median)), x1 = std::max(x1, std::log10(r.runs[i].total.median));
    y0 = std::min(y0, std::log10(errorOf(i))), y1 = std::max(y1, std::log10(errorOf(i)));
  }
  if (runs.empty()) x0 = 0, x1 = 1, y0 = -3, y1 = 0;
  // The converged reference's own noise: a dotted floor per image size, inside the axis.
  const auto floors = referenceNoiseOn(r, axis);
  for (auto& [preset, noise] : floors)
    if (noise > 0.0)
      y0 = std::min(y0, std::log10(std::max(noise, kExact))), y1 = std::max(y1, std::log10(std::max(noise, kExact)));
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

  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"12\" role=\"img\" aria-label=\"speed against error\" data-axis=\"{2}\">\n"
      "<style>.label{{font-size:{3}px}} .label.hidden{{display:none}} .show-all .label.hidden, "
      ".pt:hover .label.hidden{{display:inline}} .pt:hover .label{{font-weight:bold}}</style>\n"
      "<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
      W, H, toString(axis), kLabelFont);
  s += fmt::format("<text x=\"{}\" y=\"18\" font-size=\"14\">Speed against error: {}</text>\n", left,
                   escapeMarkup(r.info.value("sceneName", std::string("scene"))));
  for (double t : logTicks(x0, x1)) {
    double x = left + (t - x0) / (x1 - x0) * pw;
    s += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>"
        "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4}</text>\n",
        x, top, top + ph, top + ph + 16, tickLabel(t));
  }
  for (double t : logTicks(y0, y1)) {
    double y = top + (1.0 - (t - y0) / (y1 - y0)) * ph;
    bool exact = anyExact && std::abs(t - std::log10(kExact)) < 1e-9;
    s += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
        "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>\n",
        left, y, left + pw, left - 6, y + 4, exact ? "&#8804;1e-4" : tickLabel(t));
  }
  s += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333\"/>\n", left, top,
                   pw, ph);
  s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">median ms per frame (log)</text>\n", left + pw / 2,
                   H - 10);
  s += fmt::format("<text transform=\"translate(16 {}) rotate(-90)\" text-anchor=\"middle\">{} (log)</text>\n",
                   top + ph / 2, escapeMarkup(errorAxisName(r, axis)));

  for (auto& [preset, noise] : floors) {
    if (!(noise > 0.0)) continue;
    const double y = Y(std::max(noise, kExact));
    const std::string size = floors.size() > 1 ? fmt::format(" ({}x{})", preset->width, preset->height) : "";
    s += fmt::format(
        "<g class=\"reference-noise\"><line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" "
        "stroke=\"#555\" stroke-dasharray=\"1,3\"/><text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\" "
        "fill=\"#555\">reference noise{5} {6:.2g}</text></g>\n",
        left, y, left + pw, left + pw - 4, y - 4, size, noise);
  }

  // Pareto front (dashed steps), then one curve per technique.
  std::vector<std::pair<double, double>> pts;
  for (auto i : runs) pts.emplace_back(r.runs[i].total.median, errorOf(i));
  std::vector<std::size_t> front;  // indices into `runs`
  for (auto i : paretoRuns(r, axis))
    front.push_back(std::size_t(std::find(runs.begin(), runs.end(), i) - runs.begin()));
  if (front.size() > 1) {
    std::string path;
    for (std::size_t k = 0; k < front.size(); ++k) {
      double x = X(pts[front[k]].first), y = Y(pts[front[k]].second);
      if (k == 0)
        path += fmt::format("M{:.1f},{:.1f}", x, y);
      else
        path += fmt::format(" H{:.1f} V{:.1f}", x, y);
    }
    s += "<path class=\"pareto\" d=\"" + path + "\" fill=\"none\" stroke=\"#888\" stroke-dasharray=\"5,4\"/>\n";
  }
  for (auto& name : names) {
    std::vector<std::size_t> mine;
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (r.runs[runs[k]].technique == name) mine.push_back(k);
    std::sort(mine.begin(), mine.end(), [&](auto a, auto b) { return pts[a].first < pts[b].first; });
    if (mine.size() < 2) continue;
    std::string path;
    for (std::size_t k = 0; k < mine.size(); ++k)
      path += fmt::format("{}{:.1f},{:.1f}", k ? " L" : "M", X(pts[mine[k]].first), Y(pts[mine[k]].second));
    s += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.2\" opacity=\"0.7\"/>\n", path,
                     looks[name].colour);
  }

  // Labels: the Pareto front first (by time), then each family's best point (lowest error,
  // then fastest); each at the first of eight places around its point that stays inside the
  // plot and clear of every point and every label placed before it.
  const bool sweep = r.presets.size() > 1;
  auto labelText = [&](std::size_t k) {
    const CompareRun& run = r.runs[runs[k]];
    const std::string preset = sweep ? presetShort(r.presets[run.preset].label) : "";
    return std::pair(run.technique, preset.empty() ? std::string() : " " + preset);
  };
  std::vector<std::size_t> wanted(front.begin(), front.end());
  for (TechniqueFamily f : kTechniqueFamilies) {
    std::size_t best = runs.size();
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (r.runs[runs[k]].family == f && (best == runs.size() || pts[k].second < pts[best].second ||
                                          (pts[k].second == pts[best].second && pts[k].first < pts[best].first)))
        best = k;
    if (best < runs.size() && std::find(wanted.begin(), wanted.end(), best) == wanted.end()) wanted.push_back(best);
  }
  constexpr double kR = 4.5;
  std::vector<Box> taken;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const double x = X(pts[k].first), y = Y(pts[k].second);
    taken.push_back({x - kR - 1, y - kR - 1, x + kR + 1, y + kR + 1});
  }
  const Box area{left + 1, top + 1, left + pw - 1, top + ph - 1};
  struct Placed {
    double x, y;
    const char* anchor;
    bool shown;
    bool leader = false;  // drawn away from its point, joined to it by a line from (lx0, ly0) to (lx1, ly1)
    double lx0 = 0, ly0 = 0, lx1 = 0, ly1 = 0;
  };
  std::vector<Placed> placed(runs.size());
  auto place = [&](std::size_t k, bool keep) {
    const double x = X(pts[k].first), y = Y(pts[k].second);
    auto [name, preset] = labelText(k);
    const double w = kCharWidth * double(name.size() + preset.size()) + 2, d = kR + 3;
    struct Try {
      double dx, dy;  // baseline anchor point
      const char* anchor;
    };
    const Try tries[] = {{d, 3.5, "start"},    {-d, 3.5, "end"},        {0, -d - 1, "middle"}, {0, d + 9, "middle"},
                         {d - 1, -d, "start"}, {d - 1, d + 8, "start"}, {-d + 1, -d, "end"},   {-d + 1, d + 8, "end"}};
    auto fits = [&](const Box& b) {
      return b.x0 >= area.x0 && b.x1 <= area.x1 && b.y0 >= area.y0 && b.y1 <= area.y1 &&
             std::none_of(taken.begin(), taken.end(), [&](const Box& o) { return o.overlaps(b); });
    };
    for (const Try& t : tries) {
      const double bx = x + t.dx, by = y + t.dy;
      const double x0b = t.anchor[0] == 's' ? bx : t.anchor[0] == 'e' ? bx - w : bx - w / 2;
      const Box b{x0b - 1, by - kLabelFont, x0b + w + 1, by + 3};
      if (!fits(b)) continue;
      if (keep) taken.push_back(b);
      placed[k] = {bx, by, t.anchor, keep};
      return true;
    }
    // A label the plot must show (front, family best) that found no room beside its point goes
    // to the nearest free place further out, centred on rings of growing radius, with a leader
    // line back to the point: in a crowded corner of the plot (the default scene's single-map
    // family) the eight places are often all taken, and which ones depends on the timings.
    if (keep) {
      constexpr int kAngles = 16;
      for (double radius = 2 * d + 6; radius <= 0.5 * std::max(pw, ph); radius += 6)
        for (int a = 0; a < kAngles; ++a) {
          const double phi = 2 * M_PI * a / kAngles, cx = x + radius * std::cos(phi), cy = y + radius * std::sin(phi);
          const Box b{cx - w / 2 - 1, cy - kLabelFont / 2 - 1.5, cx + w / 2 + 1, cy + kLabelFont / 2 + 1.5};
          if (!fits(b)) continue;
          taken.push_back(b);
          // The line from the marker's edge to the nearest point of the label's box.
          const double ex = std::clamp(x, b.x0, b.x1), ey = std::clamp(y, b.y0, b.y1);
          const double len = std::hypot(ex - x, ey - y), ux = (ex - x) / len, uy = (ey - y) / len;
          placed[k] = {cx, cy + 3.5, "middle", true, true, x + ux * (kR + 1), y + uy * (kR + 1), ex, ey};
          return true;
        }
    }
    placed[k] = {x + d, y + 3.5, "start", false};  // no room: on hover only, at the right
    return false;
  };
  for (std::size_t k : wanted) place(k, true);
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (std::find(wanted.begin(), wanted.end(), k) == wanted.end()) place(k, false);

  for (std::size_t k = 0; k < runs.size(); ++k) {
    const CompareRun& run = r.runs[runs[k]];
    const Look& look = looks[run.technique];
    const bool onFront = std::find(front.begin(), front.end(), k) != front.end();
    const std::string ids = fmt::format("data-technique=\"{}\" data-family=\"{}\"", escapeMarkup(run.technique),
                                        escapeMarkup(toString(run.family)));
    auto [name, preset] = labelText(k);
    s += fmt::format("<g class=\"pt\" {}>\n", ids);
    s += marker(
        look.shape, X(pts[k].first), Y(pts[k].second), onFront ? 5 : 4,
        fmt::format("class=\"point\" {} fill=\"{}\" stroke=\"{}\" stroke-width=\"{}\"", ids, look.colour,
                    onFront ? "#000" : "white", onFront ? 1.5 : 1),
        fmt::format("<title>{}: {:.2f} ms, {} {:.4g}{}</title>", escapeMarkup(runLabel(r, run)), run.total.median,
                    escapeMarkup(errorAxisName(r, axis)), run.errorOn(axis), onFront ? " (Pareto front)" : ""));
    if (placed[k].leader)
      s += fmt::format(
          "<line class=\"leader\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#999\" "
          "stroke-width=\"0.8\"/>\n",
          placed[k].lx0, placed[k].ly0, placed[k].lx1, placed[k].ly1);
    const bool isWanted = std::find(wanted.begin(), wanted.end(), k) != wanted.end();
    s += fmt::format(
        "<text class=\"label{}\"{} {} x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"{}\">{}<tspan "
        "fill=\"#555\">{}</tspan></text>\n",
        placed[k].shown ? "" : " hidden", isWanted ? " data-wanted=\"1\"" : "", ids, placed[k].x, placed[k].y,
        placed[k].anchor, escapeMarkup(name), escapeMarkup(preset));
    s += "</g>\n";
  }

  // The legend, grouped by family.
  double ly = top + 8;
  const double lx = left + pw + 14;
  for (TechniqueFamily f : kTechniqueFamilies) {
    if (std::none_of(names.begin(), names.end(), [&](auto& n) { return familyOf[n] == f; })) continue;
    s += fmt::format("<text class=\"family\" x=\"{}\" y=\"{:.1f}\" font-weight=\"bold\" fill=\"{}\">{}</text>\n",
                     lx - 6, ly + 4, familyColour(f), escapeMarkup(toString(f)));
    ly += line;
    for (auto& n : names) {
      if (familyOf[n] != f) continue;
      s += marker(looks[n].shape, lx, ly, 4, fmt::format("fill=\"{}\"", looks[n].colour), "") +
           fmt::format("<text x=\"{}\" y=\"{:.1f}\">{}</text>\n", lx + 10, ly + 4, escapeMarkup(n));
      ly += line;
    }
  }
  ly += 4;
  s += fmt::format(
      "<line x1=\"{}\" y1=\"{:.1f}\" x2=\"{}\" y2=\"{:.1f}\" stroke=\"#888\" stroke-dasharray=\"5,4\"/>"
      "<text x=\"{}\" y=\"{:.1f}\">Pareto front</text>\n",
      lx - 6, ly, lx + 6, ly, lx + 10, ly + 4);
  s += "</svg>\n";
  return s;
}

}  // namespace penumbra
