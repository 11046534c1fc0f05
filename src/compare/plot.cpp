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

// A log10 range widened to at least half a decade and padded by 6% a side.
void padLogRange(double& lo, double& hi) {
  if (hi - lo < 0.5) {
    const double mid = 0.5 * (lo + hi);
    lo = mid - 0.25, hi = mid + 0.25;
  }
  const double p = 0.06 * (hi - lo);
  lo -= p, hi += p;
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

namespace {

// The plot of one axis, drawn in named steps: the techniques' looks by family, the axes fitted to
// the points and the reference's noise, the frame, the Pareto front and each technique's curve,
// the labels placed, the points, the legend.
class SpeedErrorPlot {
 public:
  SpeedErrorPlot(const CompareResult& r, ErrorAxis axis) : r_(r), axis_(axis), runs_(plottedRuns(r, axis)) {
    chooseLooks();
    fitAxes();
  }

  std::string svg() {
    std::string s = frame() + referenceNoise() + curves();
    placeLabels();
    return s + points() + legend() + "</svg>\n";
  }

 private:
  static constexpr double kLeft = 70, kRight = 200, kTop = 30, kBottom = 50, kWidth = 800, kLine = 14;
  static constexpr double kMarker = 4.5;  // a point's radius, for the labels' clearance

  // A label's place: at (x, y) with its anchor, shown or on hover only; drawn away from its point,
  // joined to it by a line from (lx0, ly0) to (lx1, ly1), when leader is set.
  struct Placed {
    double x, y;
    const char* anchor;
    bool shown;
    bool leader = false;
    double lx0 = 0, ly0 = 0, lx1 = 0, ly1 = 0;
  };

  double X(double ms) const { return kLeft + (std::log10(ms) - x0_) / (x1_ - x0_) * pw_; }
  double Y(double e) const { return kTop + (1.0 - (std::log10(e) - y0_) / (y1_ - y0_)) * ph_; }
  double errorOf(std::size_t i) const { return std::max(r_.runs[i].errorOn(axis_), kExactErrorFloor); }
  TechniqueFamily familyOf(const std::string& name) const { return familyOf_.at(name); }
  bool wanted(std::size_t k) const { return std::find(wanted_.begin(), wanted_.end(), k) != wanted_.end(); }

  // Techniques grouped by family (in the families' order), each family's in first-appearance
  // order; a look per technique (colour by family, shape and shade by variant).
  void chooseLooks() {
    for (auto i : runs_) familyOf_.emplace(r_.runs[i].technique, r_.runs[i].family);
    for (TechniqueFamily f : kTechniqueFamilies)
      for (auto i : runs_)
        if (r_.runs[i].family == f && std::find(names_.begin(), names_.end(), r_.runs[i].technique) == names_.end())
          names_.push_back(r_.runs[i].technique);
    std::map<TechniqueFamily, int> variants;
    for (auto& n : names_) looks_.emplace(n, lookOf(familyOf(n), variants[familyOf(n)]++));
    for (TechniqueFamily f : kTechniqueFamilies)
      familiesShown_ += std::any_of(names_.begin(), names_.end(), [&](auto& n) { return familyOf(n) == f; });
  }

  // The plot's size (tall enough for the legend) and its log ranges: every point and the
  // converged reference's noise floors, padded.
  void fitAxes() {
    const double legendHeight = kLine * double(names_.size() + std::size_t(familiesShown_)) + 30.0;
    height_ = std::max(480.0, kTop + legendHeight + kBottom);
    pw_ = kWidth - kLeft - kRight, ph_ = height_ - kTop - kBottom;
    for (auto i : runs_) anyExact_ |= r_.runs[i].errorOn(axis_) < kExactErrorFloor;
    x0_ = INFINITY, x1_ = -INFINITY, y0_ = INFINITY, y1_ = -INFINITY;
    for (auto i : runs_) {
      x0_ = std::min(x0_, std::log10(r_.runs[i].total.median)),
      x1_ = std::max(x1_, std::log10(r_.runs[i].total.median));
      y0_ = std::min(y0_, std::log10(errorOf(i))), y1_ = std::max(y1_, std::log10(errorOf(i)));
    }
    if (runs_.empty()) x0_ = 0, x1_ = 1, y0_ = -3, y1_ = 0;
    floors_ = referenceNoiseOn(r_, axis_);
    for (auto& [preset, noise] : floors_)
      if (noise > 0.0) {
        const double y = std::log10(std::max(noise, kExactErrorFloor));
        y0_ = std::min(y0_, y), y1_ = std::max(y1_, y);
      }
    padLogRange(x0_, x1_), padLogRange(y0_, y1_);
    for (auto i : runs_) pts_.emplace_back(r_.runs[i].total.median, errorOf(i));
  }

  // The document's head, title, ticks and grid, the frame and the axes' titles.
  std::string frame() const {
    std::string s = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
        "font-family=\"sans-serif\" font-size=\"12\" role=\"img\" aria-label=\"speed against error\" "
        "data-axis=\"{2}\">\n"
        "<style>.label{{font-size:{3}px}} .label.hidden{{display:none}} .show-all .label.hidden, "
        ".pt:hover .label.hidden{{display:inline}} .pt:hover .label{{font-weight:bold}}</style>\n"
        "<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
        kWidth, height_, toString(axis_), kLabelFont);
    s += fmt::format("<text x=\"{}\" y=\"18\" font-size=\"14\">Speed against error: {}</text>\n", kLeft,
                     escapeMarkup(r_.info.value("sceneName", std::string("scene"))));
    for (double t : logTicks(x0_, x1_)) {
      double x = kLeft + (t - x0_) / (x1_ - x0_) * pw_;
      s += fmt::format(
          "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>"
          "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4}</text>\n",
          x, kTop, kTop + ph_, kTop + ph_ + 16, tickLabel(t));
    }
    for (double t : logTicks(y0_, y1_)) {
      double y = kTop + (1.0 - (t - y0_) / (y1_ - y0_)) * ph_;
      bool exact = anyExact_ && std::abs(t - std::log10(kExactErrorFloor)) < 1e-9;
      s += fmt::format(
          "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
          "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>\n",
          kLeft, y, kLeft + pw_, kLeft - 6, y + 4, exact ? "&#8804;1e-4" : tickLabel(t));
    }
    s += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333\"/>\n", kLeft,
                     kTop, pw_, ph_);
    s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">median ms per frame (log)</text>\n",
                     kLeft + pw_ / 2, height_ - 10);
    s += fmt::format("<text transform=\"translate(16 {}) rotate(-90)\" text-anchor=\"middle\">{} (log)</text>\n",
                     kTop + ph_ / 2, escapeMarkup(errorAxisName(r_, axis_)));
    return s;
  }

  // The converged reference's own noise: a dotted floor per image size, inside the axis.
  std::string referenceNoise() const {
    std::string s;
    for (auto& [preset, noise] : floors_) {
      if (!(noise > 0.0)) continue;
      const double y = Y(std::max(noise, kExactErrorFloor));
      const std::string size = floors_.size() > 1 ? fmt::format(" ({}x{})", preset->width, preset->height) : "";
      s += fmt::format(
          "<g class=\"reference-noise\"><line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" "
          "stroke=\"#555\" stroke-dasharray=\"1,3\"/><text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\" "
          "fill=\"#555\">reference noise{5} {6:.2g}</text></g>\n",
          kLeft, y, kLeft + pw_, kLeft + pw_ - 4, y - 4, size, noise);
    }
    return s;
  }

  // The Pareto front (dashed steps), then one curve per technique through its presets by time.
  std::string curves() {
    std::string s;
    for (auto i : paretoRuns(r_, axis_))
      front_.push_back(std::size_t(std::find(runs_.begin(), runs_.end(), i) - runs_.begin()));
    if (front_.size() > 1) {
      std::string path;
      for (std::size_t k = 0; k < front_.size(); ++k) {
        double x = X(pts_[front_[k]].first), y = Y(pts_[front_[k]].second);
        if (k == 0)
          path += fmt::format("M{:.1f},{:.1f}", x, y);
        else
          path += fmt::format(" H{:.1f} V{:.1f}", x, y);
      }
      s += "<path class=\"pareto\" d=\"" + path + "\" fill=\"none\" stroke=\"#888\" stroke-dasharray=\"5,4\"/>\n";
    }
    for (auto& name : names_) {
      std::vector<std::size_t> mine;
      for (std::size_t k = 0; k < runs_.size(); ++k)
        if (r_.runs[runs_[k]].technique == name) mine.push_back(k);
      std::sort(mine.begin(), mine.end(), [&](auto a, auto b) { return pts_[a].first < pts_[b].first; });
      if (mine.size() < 2) continue;
      std::string path;
      for (std::size_t k = 0; k < mine.size(); ++k)
        path += fmt::format("{}{:.1f},{:.1f}", k ? " L" : "M", X(pts_[mine[k]].first), Y(pts_[mine[k]].second));
      s += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.2\" opacity=\"0.7\"/>\n", path,
                       looks_.at(name).colour);
    }
    return s;
  }

  // A point's label: the technique's name and, in a sweep, its preset.
  std::pair<std::string, std::string> labelText(std::size_t k) const {
    const CompareRun& run = r_.runs[runs_[k]];
    const std::string preset = r_.presets.size() > 1 ? presetShort(r_.presets[run.preset].label) : "";
    return std::pair(run.technique, preset.empty() ? std::string() : " " + preset);
  }

  // Labels: the Pareto front first (by time), then each family's best point (lowest error, then
  // fastest); each at the first of eight places around its point that stays inside the plot and
  // clear of every point and every label placed before it. The rest go where there is room, shown
  // on hover.
  void placeLabels() {
    wanted_.assign(front_.begin(), front_.end());
    for (TechniqueFamily f : kTechniqueFamilies) {
      std::size_t best = runs_.size();
      for (std::size_t k = 0; k < runs_.size(); ++k)
        if (r_.runs[runs_[k]].family == f &&
            (best == runs_.size() || pts_[k].second < pts_[best].second ||
             (pts_[k].second == pts_[best].second && pts_[k].first < pts_[best].first)))
          best = k;
      if (best < runs_.size() && !wanted(best)) wanted_.push_back(best);
    }
    for (std::size_t k = 0; k < runs_.size(); ++k) {
      const double x = X(pts_[k].first), y = Y(pts_[k].second);
      taken_.push_back({x - kMarker - 1, y - kMarker - 1, x + kMarker + 1, y + kMarker + 1});
    }
    placed_.resize(runs_.size());
    for (std::size_t k : wanted_) place(k, true);
    for (std::size_t k = 0; k < runs_.size(); ++k)
      if (!wanted(k)) place(k, false);
  }

  bool fits(const Box& b) const {
    const Box area{kLeft + 1, kTop + 1, kLeft + pw_ - 1, kTop + ph_ - 1};
    return b.x0 >= area.x0 && b.x1 <= area.x1 && b.y0 >= area.y0 && b.y1 <= area.y1 &&
           std::none_of(taken_.begin(), taken_.end(), [&](const Box& o) { return o.overlaps(b); });
  }

  // Places point k's label (and reserves its box when `keep`); returns whether it found room.
  bool place(std::size_t k, bool keep) {
    const double x = X(pts_[k].first), y = Y(pts_[k].second);
    auto [name, preset] = labelText(k);
    const double w = kCharWidth * double(name.size() + preset.size()) + 2, d = kMarker + 3;
    struct Try {
      double dx, dy;  // baseline anchor point
      const char* anchor;
    };
    const Try tries[] = {{d, 3.5, "start"},    {-d, 3.5, "end"},        {0, -d - 1, "middle"}, {0, d + 9, "middle"},
                         {d - 1, -d, "start"}, {d - 1, d + 8, "start"}, {-d + 1, -d, "end"},   {-d + 1, d + 8, "end"}};
    for (const Try& t : tries) {
      const double bx = x + t.dx, by = y + t.dy;
      const double x0b = t.anchor[0] == 's' ? bx : t.anchor[0] == 'e' ? bx - w : bx - w / 2;
      const Box b{x0b - 1, by - kLabelFont, x0b + w + 1, by + 3};
      if (!fits(b)) continue;
      if (keep) taken_.push_back(b);
      placed_[k] = {bx, by, t.anchor, keep};
      return true;
    }
    // A label the plot must show (front, family best) that found no room beside its point goes
    // to the nearest free place further out, centred on rings of growing radius, with a leader
    // line back to the point: in a crowded corner of the plot (the default scene's single-map
    // family) the eight places are often all taken, and which ones depends on the timings.
    if (keep) {
      constexpr int kAngles = 16;
      for (double radius = 2 * d + 6; radius <= 0.5 * std::max(pw_, ph_); radius += 6)
        for (int a = 0; a < kAngles; ++a) {
          const double phi = 2 * M_PI * a / kAngles, cx = x + radius * std::cos(phi), cy = y + radius * std::sin(phi);
          const Box b{cx - w / 2 - 1, cy - kLabelFont / 2 - 1.5, cx + w / 2 + 1, cy + kLabelFont / 2 + 1.5};
          if (!fits(b)) continue;
          taken_.push_back(b);
          // The line from the marker's edge to the nearest point of the label's box.
          const double ex = std::clamp(x, b.x0, b.x1), ey = std::clamp(y, b.y0, b.y1);
          const double len = std::hypot(ex - x, ey - y), ux = (ex - x) / len, uy = (ey - y) / len;
          placed_[k] = {cx, cy + 3.5, "middle", true, true, x + ux * (kMarker + 1), y + uy * (kMarker + 1), ex, ey};
          return true;
        }
    }
    placed_[k] = {x + d, y + 3.5, "start", false};  // no room: on hover only, at the right
    return false;
  }

  // Each point as a group: its marker (with a <title>), its leader line, its label.
  std::string points() const {
    std::string s;
    for (std::size_t k = 0; k < runs_.size(); ++k) {
      const CompareRun& run = r_.runs[runs_[k]];
      const Look& look = looks_.at(run.technique);
      const bool onFront = std::find(front_.begin(), front_.end(), k) != front_.end();
      const std::string ids = fmt::format("data-technique=\"{}\" data-family=\"{}\"", escapeMarkup(run.technique),
                                          escapeMarkup(toString(run.family)));
      auto [name, preset] = labelText(k);
      s += fmt::format("<g class=\"pt\" {}>\n", ids);
      s += marker(
          look.shape, X(pts_[k].first), Y(pts_[k].second), onFront ? 5 : 4,
          fmt::format("class=\"point\" {} fill=\"{}\" stroke=\"{}\" stroke-width=\"{}\"", ids, look.colour,
                      onFront ? "#000" : "white", onFront ? 1.5 : 1),
          fmt::format("<title>{}: {:.2f} ms, {} {:.4g}{}</title>", escapeMarkup(runLabel(r_, run)), run.total.median,
                      escapeMarkup(errorAxisName(r_, axis_)), run.errorOn(axis_), onFront ? " (Pareto front)" : ""));
      const Placed& p = placed_[k];
      if (p.leader)
        s += fmt::format(
            "<line class=\"leader\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#999\" "
            "stroke-width=\"0.8\"/>\n",
            p.lx0, p.ly0, p.lx1, p.ly1);
      s += fmt::format(
          "<text class=\"label{}\"{} {} x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"{}\">{}<tspan "
          "fill=\"#555\">{}</tspan></text>\n",
          p.shown ? "" : " hidden", wanted(k) ? " data-wanted=\"1\"" : "", ids, p.x, p.y, p.anchor, escapeMarkup(name),
          escapeMarkup(preset));
      s += "</g>\n";
    }
    return s;
  }

  // The legend, grouped by family, and the Pareto front's dash.
  std::string legend() const {
    std::string s;
    double ly = kTop + 8;
    const double lx = kLeft + pw_ + 14;
    for (TechniqueFamily f : kTechniqueFamilies) {
      if (std::none_of(names_.begin(), names_.end(), [&](auto& n) { return familyOf(n) == f; })) continue;
      s += fmt::format("<text class=\"family\" x=\"{}\" y=\"{:.1f}\" font-weight=\"bold\" fill=\"{}\">{}</text>\n",
                       lx - 6, ly + 4, familyColour(f), escapeMarkup(toString(f)));
      ly += kLine;
      for (auto& n : names_) {
        if (familyOf(n) != f) continue;
        s += marker(looks_.at(n).shape, lx, ly, 4, fmt::format("fill=\"{}\"", looks_.at(n).colour), "") +
             fmt::format("<text x=\"{}\" y=\"{:.1f}\">{}</text>\n", lx + 10, ly + 4, escapeMarkup(n));
        ly += kLine;
      }
    }
    ly += 4;
    s += fmt::format(
        "<line x1=\"{}\" y1=\"{:.1f}\" x2=\"{}\" y2=\"{:.1f}\" stroke=\"#888\" stroke-dasharray=\"5,4\"/>"
        "<text x=\"{}\" y=\"{:.1f}\">Pareto front</text>\n",
        lx - 6, ly, lx + 6, ly, lx + 10, ly + 4);
    return s;
  }

  const CompareResult& r_;
  const ErrorAxis axis_;
  const std::vector<std::size_t> runs_;         // the plotted runs (indices into r_.runs)
  std::vector<std::pair<double, double>> pts_;  // per plotted run: median ms, error floored
  std::vector<std::string> names_;
  std::map<std::string, TechniqueFamily> familyOf_;
  std::map<std::string, Look> looks_;
  int familiesShown_ = 0;
  double height_ = 0, pw_ = 0, ph_ = 0;       // the document's height, the plot area's size
  double x0_ = 0, x1_ = 0, y0_ = 0, y1_ = 0;  // log10 ranges
  bool anyExact_ = false;
  std::vector<std::pair<const ComparePreset*, double>> floors_;
  std::vector<std::size_t> front_, wanted_;  // indices into runs_
  std::vector<Box> taken_;
  std::vector<Placed> placed_;
};

}  // namespace

std::string speedErrorSvg(const CompareResult& r, ErrorAxis axis) { return SpeedErrorPlot(r, axis).svg(); }

std::string lineChartSvg(const std::string& title, const std::string& xLabel, const std::string& yLabel,
                         const std::vector<ChartSeries>& series) {
  constexpr double kLeft = 70, kRight = 200, kTop = 30, kBottom = 50, kWidth = 800, kLine = 14;
  std::map<TechniqueFamily, int> variants;
  std::vector<Look> looks;
  for (const ChartSeries& c : series) looks.push_back(lookOf(c.family, variants[c.family]++));
  const double legend = kLine * double(series.size() + variants.size()) + 30.0;
  const double height = std::max(420.0, kTop + legend + kBottom), pw = kWidth - kLeft - kRight,
               ph = height - kTop - kBottom;
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  const auto floored = [](double e) { return std::max(e, kExactErrorFloor); };
  for (const ChartSeries& c : series)
    for (auto [x, e] : c.points) {
      if (!(x > 0.0) || !std::isfinite(e)) continue;
      x0 = std::min(x0, std::log10(x)), x1 = std::max(x1, std::log10(x));
      y0 = std::min(y0, std::log10(floored(e))), y1 = std::max(y1, std::log10(floored(e)));
    }
  if (!(x1 >= x0)) x0 = 0, x1 = 1, y0 = -3, y1 = 0;
  padLogRange(x0, x1), padLogRange(y0, y1);
  const auto X = [&](double x) { return kLeft + (std::log10(x) - x0) / (x1 - x0) * pw; };
  const auto Y = [&](double e) { return kTop + (1.0 - (std::log10(floored(e)) - y0) / (y1 - y0)) * ph; };
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"12\" role=\"img\" aria-label=\"{2}\">\n"
      "<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n"
      "<text x=\"{3}\" y=\"18\" font-size=\"14\">{2}</text>\n",
      kWidth, height, escapeMarkup(title), kLeft);
  for (double t : logTicks(x0, x1)) {
    const double x = kLeft + (t - x0) / (x1 - x0) * pw;
    s += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>"
        "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4}</text>\n",
        x, kTop, kTop + ph, kTop + ph + 16, tickLabel(t));
  }
  for (double t : logTicks(y0, y1)) {
    const double y = kTop + (1.0 - (t - y0) / (y1 - y0)) * ph;
    s += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
        "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>\n",
        kLeft, y, kLeft + pw, kLeft - 6, y + 4, tickLabel(t));
  }
  s += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333\"/>\n", kLeft, kTop,
                   pw, ph);
  s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{} (log)</text>\n", kLeft + pw / 2, height - 10,
                   escapeMarkup(xLabel));
  s += fmt::format("<text transform=\"translate(16 {}) rotate(-90)\" text-anchor=\"middle\">{} (log)</text>\n",
                   kTop + ph / 2, escapeMarkup(yLabel));
  for (std::size_t i = 0; i < series.size(); ++i) {
    const ChartSeries& c = series[i];
    std::string path;
    for (auto [x, e] : c.points)
      if (x > 0.0 && std::isfinite(e)) path += fmt::format("{}{:.1f},{:.1f}", path.empty() ? "M" : " L", X(x), Y(e));
    s += fmt::format(
        "<g class=\"series\" data-technique=\"{}\"><path d=\"{}\" fill=\"none\" stroke=\"{}\" "
        "stroke-width=\"1.5\"/>\n",
        escapeMarkup(c.name), path, looks[i].colour);
    for (auto [x, e] : c.points)
      if (x > 0.0 && std::isfinite(e))
        s += marker(looks[i].shape, X(x), Y(e), 3.5, fmt::format("fill=\"{}\"", looks[i].colour),
                    fmt::format("<title>{}: {:.3g}, {:.4g}</title>", escapeMarkup(c.name), x, e));
    s += "</g>\n";
  }
  double ly = kTop + 8;
  const double lx = kLeft + pw + 14;
  for (TechniqueFamily f : kTechniqueFamilies) {
    if (!variants.count(f)) continue;
    s += fmt::format("<text x=\"{}\" y=\"{:.1f}\" font-weight=\"bold\" fill=\"{}\">{}</text>\n", lx - 6, ly + 4,
                     familyColour(f), escapeMarkup(toString(f)));
    ly += kLine;
    for (std::size_t i = 0; i < series.size(); ++i) {
      if (series[i].family != f) continue;
      s += marker(looks[i].shape, lx, ly, 4, fmt::format("fill=\"{}\"", looks[i].colour), "") +
           fmt::format("<text x=\"{}\" y=\"{:.1f}\">{}</text>\n", lx + 10, ly + 4, escapeMarkup(series[i].name));
      ly += kLine;
    }
  }
  return s + "</svg>\n";
}

}  // namespace penumbra
