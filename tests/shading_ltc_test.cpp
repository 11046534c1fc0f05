// The LTC GGX table (src/shading/ltc.h) and the shader's integral over it (shading/shaders/shading.h
// penumbraLightPolygon), GL-free: the fit reproduces the checked-in table bit for bit, the
// shader's transform is the fit's lobe, the polygon integral's error against the true lobe, and
// the file's bad-input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "core/error.h"
#include "floor_quadrature.h"
#include "shading/shading_shared.hpp"
#include "shading/ltc.h"

namespace penumbra::test {
namespace {

using shading::LtcTable;

std::string lutPath() { return std::string(PENUMBRA_SOURCE_DIR) + "/luts/ltc_ggx.lut"; }

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The cell's M^-1 and terms exactly (grid points: no interpolation).
const glm::vec4& cellMinv(const LtcTable& t, int a, int row) {
  return t.minv[std::size_t(row) * std::size_t(t.size()) + std::size_t(a)];
}
const glm::vec4& cellTerms(const LtcTable& t, int a, int row) {
  return t.terms[std::size_t(row) * std::size_t(t.size()) + std::size_t(a)];
}

// Unit vector at polar angle theta from z, azimuth phi from x.
glm::dvec3 direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

}  // namespace

// The checked-in table is what the code fits (reproducible byte for byte):
// the embedded copy is the file's bytes, and a fresh fit of column 13's first 53 view rows (with
// the t = 0 column it starts from) gives exactly those cells: the rows where a warm start alone
// once went astray, in about a third of the two columns' time this test took (44 s under the
// sanitizers). The whole fit: `penumbra lut --ltc` (3 minutes on 2 cores), luts/README.md.
TEST(Ltc, TheFitReproducesTheCheckedInTable) {
  const LtcTable& builtin = shading::builtinLtcTable();
  const LtcTable file = shading::readLtcTable(lutPath());
  ASSERT_EQ(file.size(), builtin.size());
  EXPECT_EQ(std::memcmp(file.minv.data(), builtin.minv.data(), file.minv.size() * sizeof(glm::vec4)), 0);
  EXPECT_EQ(std::memcmp(file.terms.data(), builtin.terms.data(), file.terms.size() * sizeof(glm::vec4)), 0);

  const int column = 13, rows = 53;
  shading::LtcFitOptions o = builtin.fit;
  o.rows = rows;
  const LtcTable fresh = shading::fitLtcGgx(o, {column});
  const int n = builtin.size();
  int compared = 0;
  for (int row = 0; row < rows; ++row)
    for (int a = 0; a < n; ++a) {
      if (row != 0 && a != column) continue;
      ASSERT_EQ(std::memcmp(&cellMinv(fresh, a, row), &cellMinv(builtin, a, row), sizeof(glm::vec4)), 0)
          << "M^-1 of cell (" << a << ", " << row << ")";
      ASSERT_EQ(std::memcmp(&cellTerms(fresh, a, row), &cellTerms(builtin, a, row), sizeof(glm::vec4)), 0)
          << "terms of cell (" << a << ", " << row << ")";
      ++compared;
    }
  EXPECT_EQ(compared, n + rows - 1);
}

// The fit is continuous: no cell's L1 error (the terms' z) jumps from its neighbour's along the
// view or the roughness, below the last two rows (the horizon, where the error grows fast: 0.37
// on average in the last row). A warm start gone astray shows as such a jump (a first L1 fit
// went from 5% to 166% at one cell of column 13 and stayed above 50% down the column);
// measured: at most 0.086 along the view, 0.040 along roughness.
TEST(Ltc, TheCheckedInFitIsContinuous) {
  const LtcTable& t = shading::builtinLtcTable();
  const int n = t.size();
  double alongView = 0.0, alongRoughness = 0.0;
  for (int row = 0; row < n - 2; ++row)
    for (int a = 0; a < n; ++a) {
      const double e = cellTerms(t, a, row).z;
      if (row > 0) alongView = std::max(alongView, std::abs(e - double(cellTerms(t, a, row - 1).z)));
      if (a > 0) alongRoughness = std::max(alongRoughness, std::abs(e - double(cellTerms(t, a - 1, row).z)));
    }
  std::printf("largest step of the L1 error between neighbouring cells: %.3f along the view, %.3f along roughness\n",
              alongView, alongRoughness);
  EXPECT_LE(alongView, 0.1);
  EXPECT_LE(alongRoughness, 0.06);
}

// The shader's integral (penumbraLightPolygon: the frame from n and v, M^-1 from the table's four
// numbers, Lambert's formula) is the fitted lobe the fit evaluates (ltcCellLobe): a small square
// around direction l integrates to the integral of g / norm over it (midpoint rule), on both sides
// of the view plane and behind the normal from v. Catches a transposed matrix or a mirrored frame.
TEST(Ltc, TheShaderIntegralIsTheFittedLobe) {
  const LtcTable& t = shading::builtinLtcTable();
  const int n = t.size();
  double worst = 0.0;
  int checked = 0;
  for (int a : {12, 30, 50})
    for (int row : {0, 20, 40, 55}) {
      const glm::dvec3 v = shading::ltcCellView(n, row);
      for (double theta : {0.2, 0.6, 1.0})
        for (double phi : {0.0, 1.0, 2.5, 4.0}) {
          const glm::dvec3 l = direction(theta, phi);
          const double g = shading::ltcCellLobe(t, a, row, l);
          if (g < 1e-3 * double(cellTerms(t, a, row).x)) continue;  // the tail: relative error meaningless
          // A square of side 2h at distance 1 along l, facing it; the fit's lobe integrated over it
          // by the midpoint rule (dw = dA cos / r^2).
          const double h = 0.05;
          const glm::dvec3 e1 = glm::normalize(glm::cross(l, glm::dvec3(0.3, 0.7, 0.1)));
          const glm::dvec3 e2 = glm::cross(l, e1);
          const int m = 64;
          double expected = 0.0;
          for (int j = 0; j < m; ++j)
            for (int i = 0; i < m; ++i) {
              const glm::dvec3 x = l + ((i + 0.5) / m * 2.0 - 1.0) * h * e1 + ((j + 0.5) / m * 2.0 - 1.0) * h * e2;
              const double r2 = glm::dot(x, x);
              expected += shading::ltcCellLobe(t, a, row, x / std::sqrt(r2)) * (2.0 * h / m) * (2.0 * h / m) /
                          (r2 * std::sqrt(r2));
            }
          expected /= double(cellTerms(t, a, row).x);
          const shared::vec3 z(0.0f, 0.0f, 1.0f);
          const double integral =
              shared::penumbraLightPolygon(PENUMBRA_LIGHT_RECT, glm::vec3(0.0f), z, z, glm::vec3(l), glm::vec3(e1),
                                           glm::vec3(e2), glm::vec2(float(h)), true, glm::vec3(v), cellMinv(t, a, row))
                  .y;
          const double rel = std::abs(integral - expected) / expected;
          if (rel > 2e-3)
            std::printf("cell (%d, %d), l at theta %.1f phi %.1f: %.5g, the fit's lobe %.5g\n", a, row, theta, phi,
                        integral, expected);
          worst = std::max(worst, rel);
          ++checked;
        }
    }
  std::printf("%d directions, worst relative difference %.3g\n", checked, worst);
  EXPECT_GT(checked, 60);
  EXPECT_LE(worst, 2e-3);
}

namespace {
// The integral over a rect (centre c at distance along direction, facing the origin) of the true
// lobe by a midpoint rule over its area, and by LTC (the table looked up as the GPU does).
struct RectCase {
  double roughness, cosThetaV, theta, phi, halfSize;
};

void rectIntegrals(const RectCase& k, double& truth, double& ltc, double& norm) {
  const LtcTable& t = shading::builtinLtcTable();
  const glm::dvec3 v(std::sqrt(1.0 - k.cosThetaV * k.cosThetaV), 0.0, k.cosThetaV);
  const glm::dvec3 c = direction(k.theta, k.phi);
  const glm::dvec3 e1 = glm::normalize(glm::cross(c, glm::dvec3(0.3, 0.7, 0.1)));
  const glm::dvec3 e2 = glm::cross(c, e1);
  const float alpha = shared::penumbraAlpha(float(k.roughness));
  const int m = 400;
  truth = 0.0;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const double s = ((i + 0.5) / m * 2.0 - 1.0) * k.halfSize, u = ((j + 0.5) / m * 2.0 - 1.0) * k.halfSize;
      const glm::dvec3 x = c + s * e1 + u * e2;
      const double r2 = glm::dot(x, x);
      const glm::dvec3 l = x / std::sqrt(r2);
      const double dw = (2.0 * k.halfSize / m) * (2.0 * k.halfSize / m) * glm::dot(l, c) / r2;
      truth += double(shared::penumbraGgxCosine(shared::vec3(0, 0, 1), glm::vec3(v), glm::vec3(l), alpha)) * dw;
    }
  const glm::vec4 minv = shading::ltcLookup(t, 0, float(k.roughness), float(k.cosThetaV));
  const glm::vec4 terms = shading::ltcLookup(t, 1, float(k.roughness), float(k.cosThetaV));
  const shared::vec3 z(0.0f, 0.0f, 1.0f);
  ltc = double(shared::penumbraLightPolygon(PENUMBRA_LIGHT_RECT, glm::vec3(0.0f), z, z, glm::vec3(c), glm::vec3(e1),
                                            glm::vec3(e2), glm::vec2(float(k.halfSize)), true, glm::vec3(v), minv)
                   .y) *
        double(terms.x);
  norm = double(terms.x);
}
}  // namespace

// What the LTC gives against the true lobe over rect lights: rects centred
// on the mirror direction, beyond it and sideways (in the lobe's tail), small (half-size 0.1 at
// distance 1) and large (0.5), for roughness 0.2-0.6 and views from normal to 75 degrees. The
// error relative to the true integral on the mirror direction, and relative to norm (the whole
// lobe: what the light adds next to what a light filling the hemisphere would) everywhere; the
// gates are the measured values (llvmpipe and the CPU agree: this test is the CPU's). The fit
// minimises the lobe's L1 error (ltc_fit.cpp), which spreads the error over the lobe: 2.7% of
// norm at worst (the paper's cubic objective: 8.1%), but a small light on the mirror direction at
// 75 degrees and roughness 0.6 gets 46% too little (before 23%; the next worst case 15%).
TEST(Ltc, PolygonIntegralAgainstTheTrueLobe) {
  double worstOn = 0.0, worstNorm = 0.0;
  for (double r : {0.2, 0.3, 0.45, 0.6})
    for (double cv : {1.0, 0.8, 0.5, 0.26})
      for (double size : {0.1, 0.5}) {
        const double thetaV = std::acos(cv);
        for (int where = 0; where < 3; ++where) {
          RectCase k{r, cv, std::max(thetaV, 0.05), std::numbers::pi, size};  // the mirror direction
          if (where == 1) k.theta = std::min(thetaV + 0.4, 1.3);
          if (where == 2) k.theta = std::max(thetaV, 0.3), k.phi = 1.0;
          double truth, ltc, norm;
          rectIntegrals(k, truth, ltc, norm);
          std::printf(
              "roughness %.2f cos(theta_v) %.2f half-size %.1f %-8s: true %.5g ltc %.5g (%+.3f, %+.4f of norm)\n", r,
              cv, size,
              where == 0   ? "mirror"
              : where == 1 ? "beyond"
                           : "sideways",
              truth, ltc, (ltc - truth) / truth, (ltc - truth) / norm);
          if (where == 0) worstOn = std::max(worstOn, std::abs(ltc - truth) / truth);
          worstNorm = std::max(worstNorm, std::abs(ltc - truth) / norm);
        }
      }
  std::printf("worst error: %.3g relative on the mirror direction, %.3g of norm in all\n", worstOn, worstNorm);
  RecordProperty("worst_mirror_relative", std::to_string(worstOn));
  RecordProperty("worst_of_norm", std::to_string(worstNorm));
  EXPECT_LE(worstOn, 0.5);
  EXPECT_LE(worstNorm, 0.03);
}

namespace {
// The LTC's unshadowed specular term on the floor of tests/floor_quadrature.h (a 1 x 0.6 rect
// light 1 above it, the eye at (0, 1.5, 3.5): the converged reference's test scene) against the
// independent quadrature of the specular term, on metal of base colour 1 (Fresnel exactly 1: the
// term is norm times the polygon integral, the table's alone) and a dielectric (f0 = 0.04:
// Schlick's factor at penumbraLtcFresnelDirection too). Relative RMSE (RMSE over the
// quadrature's RMS) over an n x n grid of floor points covering the highlight and the light's
// pool, as the shader computes it (penumbraLightPolygon, the table looked up as the GPU does).
double ltcFloorError(const LtcTable& table, double roughness, int n, double* bias = nullptr, double metallic = 1.0) {
  namespace q = quadrature;
  const q::FloorSetup s;
  const q::Brdf metal{1.0, metallic, roughness};
  const q::GaussRule rule(8);
  double se = 0.0, sum = 0.0, signedSum = 0.0, wantSum = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const glm::dvec3 p(-1.2 + 2.4 * (x + 0.5) / n, 0.0, -0.4 + 2.6 * (y + 0.5) / n);
      const double want = q::exactRadiance(s, metal, p, rule, q::Terms::Specular);
      const glm::vec3 v = glm::vec3(glm::normalize(s.eye - p)), up(0.0f, 1.0f, 0.0f);
      const glm::vec4 minv = shading::ltcLookup(table, 0, float(roughness), v.y);
      const glm::vec4 terms = shading::ltcLookup(table, 1, float(roughness), v.y);
      const glm::vec3 l = shared::penumbraLtcFresnelDirection(
          PENUMBRA_LIGHT_RECT, glm::vec3(p), up, v, glm::vec3(s.lightCentre), glm::vec3(0.0f, -1.0f, 0.0f),
          glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f), glm::vec2(float(s.halfW), float(s.halfH)),
          shared::penumbraAlpha(float(roughness)));
      const double got =
          double(shared::penumbraLightPolygon(PENUMBRA_LIGHT_RECT, glm::vec3(p), up, up, glm::vec3(s.lightCentre),
                                              glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f),
                                              glm::vec2(float(s.halfW), float(s.halfH)), true, v, minv)
                     .y) *
          double(terms.x) * metal.fresnel(glm::dot(glm::dvec3(v), glm::normalize(glm::dvec3(v) + glm::dvec3(l))));
      se += (got - want) * (got - want), sum += want * want;
      signedSum += got - want, wantSum += want;
    }
  if (bias) *bias = signedSum / wantSum;
  return std::sqrt(se / sum);
}
}  // namespace

TEST(Ltc, UnshadowedTermAgainstTheQuadratureOnRectLitFloors) {
  const LtcTable& table = shading::builtinLtcTable();
  int k = 0;
  for (double r : {0.05, 0.1, 0.3, 0.5, 0.7, 1.0}) {
    double metalBias = 0.0, dielectricBias = 0.0;
    const double metal = ltcFloorError(table, r, 24, &metalBias);
    const double dielectric = ltcFloorError(table, r, 24, &dielectricBias, 0.0);
    std::printf(
        "roughness %.2f: the LTC's specular term, relative RMSE (bias): metal %.4f (%+.4f), dielectric "
        "%.4f (%+.4f)\n",
        r, metal, metalBias, dielectric, dielectricBias);
    // Measured (the CPU's: the shader's functions compiled as C++): metal 0.0029 / 0.0021 /
    // 0.0250 / 0.0511 / 0.0237 / 0.0160, dielectric 0.0028 / 0.0023 / 0.0477 / 0.0632 / 0.0254 /
    // 0.0184 at roughness 0.05 / 0.1 / 0.3 / 0.5 / 0.7 / 1.0. The fit of 2026-12-03 (the paper's
    // cubic objective, the axis at the mean) with the hemisphere's Fresnel split: metal 0.0029 /
    // 0.0022 / 0.0443 / 0.1411 / 0.0888 / 0.0158, dielectric 0.0037 / 0.0069 / 0.1326 / 0.2865 /
    // 0.4021 / 0.1883. Gates 20% above the measured values.
    const double metalGate[] = {0.0035, 0.0026, 0.03, 0.062, 0.029, 0.02};
    const double dielectricGate[] = {0.0034, 0.0028, 0.058, 0.076, 0.031, 0.023};
    EXPECT_LE(metal, metalGate[k]) << "metal, roughness " << r;
    EXPECT_LE(dielectric, dielectricGate[k]) << "dielectric, roughness " << r;
    ++k;
  }
}

// Bad table files get one clear error each, naming the file and the cause (the header reader is
// core/table_file.h's, shared with the edge LUTs).
TEST(Ltc, BadTableFilesAreRefused) {
  const std::string good = fileBytes(lutPath());
  ASSERT_FALSE(good.empty());
  auto refuse = [&](const std::string& bytes, const std::string& what, const std::string& cause) {
    try {
      shading::parseLtcTable(bytes, "x.lut");
      ADD_FAILURE() << "accepted: " << what;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("x.lut: ", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find(cause), std::string::npos) << what << ": " << e.what();
    }
  };
  refuse("", "empty", "not a penumbra-ltc-ggx file");
  refuse("penumbra-edge-lut 2\n", "another table", "not a penumbra-ltc-ggx file");
  refuse(good.substr(0, good.size() - 7), "truncated", "payload is");
  std::string flipped = good;
  flipped[flipped.size() - 100] ^= 0x10;
  refuse(flipped, "a flipped payload bit", "checksum mismatch");
  std::string header = good;
  header.replace(header.find("size 64"), 7, "size 65");
  refuse(header, "a wrong size", "payload is");
  // An edited header value that leaves the payload's size alone: the checksum covers the header
  // (format 2; format 1's covered the payload only and passed it).
  std::string edited = good;
  edited.replace(edited.find("iterations 200"), 14, "iterations 201");
  refuse(edited, "an edited header value", "checksum mismatch");
  std::string v1 = good;
  v1.replace(0, v1.find('\n'), "penumbra-ltc-ggx 1");
  refuse(v1, "format 1", "this build reads 'penumbra-ltc-ggx 2': regenerate it");
  std::string twice = good;
  twice.insert(twice.find("checksum"), "size 64\n");
  refuse(twice, "a key given twice", "header key 'size' given twice");
  std::string unknown = good;
  unknown.insert(unknown.find("checksum"), "colour blue\n");
  refuse(unknown, "an unknown key", "unknown header line 'colour blue'");
  std::string missing = good;
  missing.erase(missing.find("iterations 200\n"), 15);
  refuse(missing, "a missing key", "incomplete header");
  // A round trip through the writer keeps every byte.
  const std::string copy = (std::filesystem::temp_directory_path() / "penumbra_ltc_copy.lut").string();
  shading::writeLtcTable(copy, shading::builtinLtcTable());
  EXPECT_EQ(fileBytes(copy), good);
  std::remove(copy.c_str());
}

}  // namespace penumbra::test
