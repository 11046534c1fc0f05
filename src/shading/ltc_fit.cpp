// The LTC GGX fit (Heitz, Dupuy, Hill and Neubelt 2016, section 4 and the authors' released
// fitLTC.cpp, which this follows in its order and sampling): per cell, norm, fresnel and the
// lobe's mean direction by importance sampling the BRDF; then M's free terms by Nelder-Mead, f the
// true lobe (shading/shaders/shading.h penumbraGgxCosine), g the LTC scaled by norm, on a deterministic stratified
// grid of MIS samples of both. Fit order as the paper's: the t = 0 (normal incidence) cell of each
// roughness column from the rougher neighbour's, isotropic (m11 = m22, m13 = 0); along the
// column, each cell warm-started from the previous one. The whole fit takes 3 minutes on 2 cores
// (the paper's objective and order: 43 s). Divergences, each measured on the floor
// of tests/shading_ltc_test.cpp (metal, relative RMSE of the unshadowed term against a
// quadrature; roughness 0.3 / 0.5 / 0.7):
// - the objective is the lobe's L1 error, mean over MIS samples of |f - g| / (p_f + p_g) (the
//   error the report states, times norm), not the paper's |f - g|^3 / (p_f + p_g), which weights
//   the peak and left the tail the light's integral also sums: 0.044 / 0.141 / 0.089 -> 0.041 /
//   0.091 / 0.039. g below the horizon counts (f = 0 there): an objective of the clipped lobe,
//   the one the renderer integrates, let the fit move mass below it and lose it (0.5: 0.052,
//   bias -5%);
// - the lobe's axis Z is a fourth parameter, an angle in the view plane from the mean direction
//   (the paper fixes Z at the mean): at grazing views the best axis is not the mean (with the L1
//   objective: 0.025 / 0.051 / 0.024). A free amplitude (norm times a fifth parameter) or norm
//   scaled so that the clipped lobe integrates to it did not help (0.028 / 0.050 / 0.024);
// - each cell from two starts, kept the better (fitColumn below);
// - alpha = penumbraAlpha(r), the renderer's clamp at PENUMBRA_MIN_ROUGHNESS, so the table holds
//   the lobe the renderer evaluates; sample counts are options; the reported error is the L1
//   error relative to norm of the LTC clipped to n's horizon (shading/shaders/shading.h penumbraLtcPolygon).
#include "shading/ltc.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>

#include "core/error.h"
#include "shading/brdf_sampling.h"
#include "shading/shading_shared.hpp"

namespace penumbra::shading {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A cell's view direction and alpha.
struct Cell {
  glm::dvec3 v;
  double alpha = 0.0;
};

Cell cellOf(int n, int a, int t) {
  Cell c;
  c.v = ltcCellView(n, t);
  c.alpha = double(shared::penumbraAlpha(float(double(a) / double(n - 1))));
  return c;
}

// The true lobe D V (n.l), n = z.
double lobe(const Cell& c, const glm::dvec3& l) {
  return double(
      shared::penumbraGgxCosine(shared::vec3(0.0f, 0.0f, 1.0f), shared::vec3(c.v), shared::vec3(l), float(c.alpha)));
}

glm::dvec3 sampleGgx(const Cell& c, double u1, double u2) { return sampleGgxReflection(c.v, c.alpha, u1, u2); }
double pdfGgx(const Cell& c, const glm::dvec3& l) { return ggxReflectionPdf(c.v, l, c.alpha); }

// An LTC lobe: M = [X Y Z] * [[m11 0 m13] [0 m22 0] [0 0 1]], amplitude norm.
struct Lobe {
  glm::dvec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  double m11 = 1.0, m22 = 1.0, m13 = 0.0, amplitude = 1.0;
  glm::dmat3 m{1.0}, minv{1.0};
  double detMinv = 1.0;

  // The frame about axis z (in the xz plane): x = y cross z, y = +y.
  void setAxis(const glm::dvec3& axis) {
    z = axis;
    x = glm::dvec3(axis.z, 0.0, -axis.x);
    y = glm::dvec3(0.0, 1.0, 0.0);
  }
  void update() {
    m = glm::dmat3(x, y, z) * glm::dmat3(m11, 0, 0, 0, m22, 0, m13, 0, 1);
    minv = glm::inverse(m);
    detMinv = std::abs(glm::determinant(minv));
  }
  // amplitude * D_o(M^-1 l / |M^-1 l|) |det M^-1| / |M^-1 l|^3 for unit l.
  double eval(const glm::dvec3& l) const {
    glm::dvec3 o = minv * l;
    double len = glm::length(o);
    double cosO = o.z / len;
    if (!(cosO > 0.0)) return 0.0;
    return amplitude * (cosO / kPi) * detMinv / (len * len * len);
  }
  glm::dvec3 sample(double u1, double u2) const { return glm::normalize(m * sampleCosine(u1, u2)); }
};

// Balance-heuristic MIS over both distributions on an ns x ns stratified grid each:
// sum of h(f, g) / (p_f + p_g) / ns^2.
template <class H>
double misMean(const Lobe& g, const Cell& c, int ns, H h) {
  double sum = 0.0;
  for (int j = 0; j < ns; ++j)
    for (int i = 0; i < ns; ++i) {
      const double u1 = (i + 0.5) / ns, u2 = (j + 0.5) / ns;
      for (int which = 0; which < 2; ++which) {
        glm::dvec3 l = which == 0 ? g.sample(u1, u2) : sampleGgx(c, u1, u2);
        double f = lobe(c, l), gl = g.eval(l);
        double p = gl / g.amplitude + pdfGgx(c, l);
        if (p > 0.0) sum += h(f, gl, l) / p;
      }
    }
  return sum / (double(ns) * ns);
}

// The fit's objective: the lobe's L1 error, g unclipped (file comment).
double objective(const Lobe& g, const Cell& c, int ns) {
  return misMean(g, c, ns, [](double f, double gl, const glm::dvec3&) { return std::abs(f - gl); });
}

// Nelder-Mead (standard coefficients 1, 2, 1/2, 1/2; start simplex `delta` along each axis; stop
// when the best and worst values agree to `tolerance` relative, as the paper's nelder_mead.h).
template <int D, class F>
std::array<double, D> nelderMead(std::array<double, D> start, double delta, double tolerance, int iterations, F f) {
  std::array<std::array<double, D>, D + 1> s;
  std::array<double, D + 1> fs;
  for (int i = 0; i <= D; ++i) {
    s[i] = start;
    if (i > 0) s[i][i - 1] += delta;
    fs[i] = f(s[i]);
  }
  auto lowest = [&] { return int(std::min_element(fs.begin(), fs.end()) - fs.begin()); };
  for (int it = 0; it < iterations; ++it) {
    int lo = lowest(), hi = 0;
    for (int i = 1; i <= D; ++i)
      if (fs[i] > fs[hi]) hi = i;
    int nh = hi == 0 ? 1 : 0;
    for (int i = 0; i <= D; ++i)
      if (i != hi && fs[i] > fs[nh]) nh = i;
    if (2.0 * std::abs(fs[lo] - fs[hi]) <= (std::abs(fs[lo]) + std::abs(fs[hi])) * tolerance) break;
    std::array<double, D> o{};
    for (int i = 0; i <= D; ++i)
      if (i != hi)
        for (int k = 0; k < D; ++k) o[k] += s[i][k] / D;
    auto along = [&](double t) {
      std::array<double, D> p;
      for (int k = 0; k < D; ++k) p[k] = o[k] + t * (o[k] - s[hi][k]);
      return p;
    };
    std::array<double, D> r = along(1.0);
    double fr = f(r);
    if (fr < fs[lo]) {
      std::array<double, D> e = along(2.0);
      double fe = f(e);
      if (fe < fr) {
        s[hi] = e, fs[hi] = fe;
        continue;
      }
    }
    if (fr < fs[nh]) {
      s[hi] = r, fs[hi] = fr;
      continue;
    }
    std::array<double, D> c = along(-0.5);
    double fc = f(c);
    if (fc < fs[hi]) {
      s[hi] = c, fs[hi] = fc;
      continue;
    }
    for (int i = 0; i <= D; ++i) {
      if (i == lo) continue;
      for (int k = 0; k < D; ++k) s[i][k] = s[lo][k] + 0.5 * (s[i][k] - s[lo][k]);
      fs[i] = f(s[i]);
    }
  }
  return s[lowest()];
}

// norm, fresnel and the mean direction (its y dropped) of a cell's lobe.
struct Moments {
  double norm = 0.0, fresnel = 0.0;
  glm::dvec3 mean{0, 0, 1};
};

Moments momentsOf(const Cell& c, int ns) {
  Moments m;
  glm::dvec3 dir(0.0);
  for (int j = 0; j < ns; ++j)
    for (int i = 0; i < ns; ++i) {
      glm::dvec3 l = sampleGgx(c, (i + 0.5) / ns, (j + 0.5) / ns);
      double p = pdfGgx(c, l);
      if (!(p > 0.0)) continue;
      double w = lobe(c, l) / p;
      double vh = std::max(glm::dot(c.v, glm::normalize(c.v + l)), 0.0);
      m.norm += w;
      m.fresnel += w * std::pow(1.0 - vh, 5.0);
      dir += w * l;
    }
  m.norm /= double(ns) * ns;
  m.fresnel /= double(ns) * ns;
  dir.y = 0.0;
  if (glm::length(dir) > 0.0) m.mean = glm::normalize(dir);
  return m;
}

// Fits `g` (its frame and start values set) to the cell; returns the objective. Anisotropic: the
// axis turns in the xz plane by the fourth parameter from the Z `g` came with.
double fitCell(Lobe& g, const Cell& c, bool isotropic, const LtcFitOptions& o) {
  auto apply = [&](double m11, double m22, double m13) {
    g.m11 = std::max(m11, 1e-7);
    g.m22 = std::max(m22, 1e-7);
    g.m13 = m13;
    g.update();
  };
  if (isotropic) {
    auto f = [&](const std::array<double, 1>& p) {
      apply(p[0], p[0], 0.0);
      return objective(g, c, o.fitSamples);
    };
    auto best = nelderMead<1>({g.m11}, 0.05, 1e-5, o.iterations, f);
    apply(best[0], best[0], 0.0);
  } else {
    const glm::dvec3 z0 = g.z;
    auto turn = [&](double angle) {
      const double ca = std::cos(angle), sa = std::sin(angle);
      g.setAxis(glm::dvec3(z0.x * ca + z0.z * sa, 0.0, z0.z * ca - z0.x * sa));
    };
    auto f = [&](const std::array<double, 4>& p) {
      turn(p[3]);
      apply(p[0], p[1], p[2]);
      return objective(g, c, o.fitSamples);
    };
    auto best = nelderMead<4>({g.m11, g.m22, g.m13, 0.0}, 0.05, 1e-5, o.iterations, f);
    turn(best[3]);
    apply(best[0], best[1], best[2]);
  }
  return objective(g, c, o.fitSamples);
}

// Stores a fitted lobe into the table's cell.
void store(LtcTable& table, int a, int t, const Lobe& g, const Cell& c, double fresnel, double objectiveValue) {
  const std::size_t i = std::size_t(t) * std::size_t(table.size()) + std::size_t(a);
  glm::dmat3 minv = g.minv / g.minv[1][1];
  table.minv[i] = glm::vec4(float(minv[0][0]), float(minv[0][2]), float(minv[2][0]), float(minv[2][2]));
  // The reported error: L1 relative to norm, of the lobe the renderer integrates (clipped at z = 0).
  double l1 = misMean(g, c, table.fit.errorSamples,
                      [](double f, double gl, const glm::dvec3& l) { return std::abs(f - (l.z > 0.0 ? gl : 0.0)); });
  table.terms[i] = glm::vec4(float(g.amplitude), float(fresnel), float(g.amplitude > 0.0 ? l1 / g.amplitude : 0.0),
                             float(objectiveValue));
}

}  // namespace

glm::dvec3 ltcCellView(int size, int t) {
  double x = double(t) / double(size - 1);
  double theta = std::min(1.57, std::acos(1.0 - x * x));
  return {std::sin(theta), 0.0, std::cos(theta)};
}

double ggxCellLobe(int size, int a, int t, const glm::dvec3& l) { return lobe(cellOf(size, a, t), l); }

double ltcCellLobe(const LtcTable& table, int a, int t, const glm::dvec3& l) {
  const std::size_t i = std::size_t(t) * std::size_t(table.size()) + std::size_t(a);
  const glm::vec4 m = table.minv[i];
  glm::dmat3 minv(glm::dvec3(m.x, 0, m.y), glm::dvec3(0, 1, 0), glm::dvec3(m.z, 0, m.w));
  glm::dvec3 o = minv * l;
  double len = glm::length(o);
  if (!(o.z > 0.0)) return 0.0;
  return double(table.terms[i].x) * (o.z / len / kPi) * std::abs(glm::determinant(minv)) / (len * len * len);
}

LtcTable fitLtcGgx(const LtcFitOptions& o, const std::vector<int>& columns,
                   const std::function<void(int, int)>& progress) {
  if (o.size < 2 || o.size > 256) throw Error("ltc fit", "table size must be in 2..256");
  if (o.fitSamples < 1 || o.momentSamples < 1 || o.errorSamples < 1 || o.iterations < 1)
    throw Error("ltc fit", "sample counts and iterations must be positive");
  const int n = o.size;
  LtcTable table;
  table.fit = o;
  table.fit.threads = 0;
  table.fit.rows = 0;
  const int rows = o.rows > 0 ? std::min(o.rows, n) : n;
  table.minv.assign(std::size_t(n) * std::size_t(n), glm::vec4(0.0f));
  table.terms = table.minv;

  // Column starts (t = 0), from the roughest down: isotropic, each from its rougher neighbour.
  std::vector<Lobe> starts(static_cast<std::size_t>(n));
  for (int a = n - 1; a >= 0; --a) {
    Cell c = cellOf(n, a, 0);
    Moments mo = momentsOf(c, o.momentSamples);
    Lobe g;
    if (a < n - 1) g.m11 = g.m22 = starts[std::size_t(a + 1)].m11;
    g.amplitude = mo.norm;
    g.update();
    double e = fitCell(g, c, true, o);
    starts[std::size_t(a)] = g;
    store(table, a, 0, g, c, mo.fresnel, e);
  }

  std::vector<int> todo = columns;
  if (todo.empty())
    for (int a = 0; a < n; ++a) todo.push_back(a);
  for (int a : todo)
    if (a < 0 || a >= n) throw Error("ltc fit", "roughness column " + std::to_string(a) + " outside the table");

  // Each column on its own: from its start cell along t, each cell from the previous fit.
  // Each column on its own, along t. A cell is fitted from two starts, the previous cell's fit
  // (the paper's warm start) and the column's t = 0 lobe (isotropic, about the cell's mean
  // direction), and keeps the better, then Nelder-Mead restarts once from it: the warm start
  // alone can follow a poor local minimum down the rest of the column (column 13 of the first
  // such fit jumped from 5% to 166% L1 error at cos(theta_v) 0.32 and stayed above 50%).
  auto fitColumn = [&](int a) {
    Lobe previous = starts[std::size_t(a)];
    for (int t = 1; t < rows; ++t) {
      Cell c = cellOf(n, a, t);
      Moments mo = momentsOf(c, o.momentSamples);
      Lobe best;
      double bestError = 0.0;
      for (int k = 0; k < 2; ++k) {
        Lobe g = k == 0 ? previous : starts[std::size_t(a)];
        g.setAxis(mo.mean);
        g.amplitude = mo.norm;
        g.update();
        const double e = fitCell(g, c, false, o);
        if (k == 0 || e < bestError) best = g, bestError = e;
      }
      bestError = fitCell(best, c, false, o);
      store(table, a, t, best, c, mo.fresnel, bestError);
      previous = best;
    }
  };
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  int done = 0;
  auto worker = [&] {
    for (std::size_t k; (k = next.fetch_add(1)) < todo.size();) {
      fitColumn(todo[k]);
      std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (progress) progress(done, int(todo.size()));
    }
  };
  int threads = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::min(threads, int(todo.size()));
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  return table;
}

}  // namespace penumbra::shading
