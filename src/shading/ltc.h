// Linearly transformed cosines for the GGX specular lobe (Heitz, Dupuy, Hill and Neubelt 2016,
// "Real-time polygonal-light shading with linearly transformed cosines", ACM TOG 35(4)): the
// table the ratio estimator's unshadowed specular term reads (shading/shaders/shading.h
// penumbraLtcPolygon, shaders/pipeline_shade.frag), its fit (`penumbra lut --ltc`) and its file.
// No GL here.
//
// The lobe is shading/shaders/shading.h penumbraGgxCosine, D V (n.l) with F = 1, the very function the per-sample
// shading and the reference evaluate; for view elevation theta_v and roughness r (alpha =
// penumbraAlpha(r)) it is approximated by
//   norm * D_o(M^-1 l / |M^-1 l|) * |det M^-1| / |M^-1 l|^3,  D_o(w) = max(w.z, 0) / pi,
// in the frame (x towards v's tangent part, y, z = n). M = [X Y Z] diag-ish(m11, m22, 1) with the
// lobe's mean direction Z in the xz plane (paper section 4 and its released fitLTC.cpp), so M^-1
// has the pattern [[a 0 b] [0 1 0] [c 0 d]] once divided by its middle element (which the polygon
// integral ignores: it is invariant to scaling each vertex). norm = integral of the lobe over the
// hemisphere; fresnel = integral of the lobe times (1 - v.h)^5 (the paper's split, f0 (norm -
// fresnel) + fresnel, of the Schlick-weighted integral over the hemisphere; kept in the table and
// its report, but the renderer takes Schlick's factor towards a point of the light instead,
// shading/shaders/shading.h penumbraLtcFresnelDirection, which is 4-15 times closer on a dielectric at roughness
// 0.3-1.0).
//
// Grid (paper): cell (a, t), a, t in 0..N-1: roughness r = a / (N - 1), view x = t / (N - 1) with
// cos(theta_v) = 1 - x^2 (theta_v at most 1.57); looked up at (r, sqrt(1 - cos theta_v)) through
// texel centres with bilinear filtering.
//
// File format (luts/ltc_ggx.lut; the header is core/table_file.h's, which every table file
// shares): a text header of `key value` lines, then the payload as little-endian float32:
//   penumbra-ltc-ggx 2
//   size N / fit-samples F / moment-samples S / error-samples E / iterations I
//   checksum <16 hex digits>  FNV-1a 64 of the lines above (each with its newline), then the
//                             payload bytes (format 1 left the header out)
//   end
// payload: minv [N][N][4] (rows by t, then a: (a, c, b, d) of M^-1 above, i.e. GLSL's mat3 columns
// (x, 0, y), (0, 1, 0), (z, 0, w)), then terms [N][N][4]: (norm, fresnel, relative L1 error of the
// fit, the fit's objective). The two arrays are the two layers of the GPU texture.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace penumbra::shading {

struct LtcFitOptions {
  int size = 64;            // N: the table is N x N cells
  int fitSamples = 32;      // the fit's objective on fitSamples^2 stratified directions per lobe (x2: MIS)
  int momentSamples = 256;  // norm, fresnel and the mean direction from momentSamples^2 BRDF samples
  int errorSamples = 64;    // the reported L1 error from errorSamples^2 directions per lobe (x2: MIS)
  int iterations = 200;     // Nelder-Mead iterations at most per cell (paper: 100, for one parameter fewer)
  int threads = 0;          // 0: hardware concurrency; the result does not depend on it
  int rows = 0;             // fit the view rows t < rows of the columns only (0: all; a row depends on
                            // the rows before it only, so this reproduces them); not stored
};

struct LtcTable {
  LtcFitOptions fit;             // what made it (threads not stored)
  std::vector<glm::vec4> minv;   // [t * N + a]
  std::vector<glm::vec4> terms;  // [t * N + a]: norm, fresnel, relative L1 error, objective
  int size() const { return fit.size; }
  bool empty() const { return minv.empty(); }
};

// Fits the table (deterministic: the same bytes for any thread count). roughnessColumns: the
// columns a whose every view cell is fitted (empty: all); the t = 0 column is always fitted
// (each column starts from its neighbour's t = 0 lobe, paper's order), other cells stay 0. A
// column's fit depends on nothing outside it and that t = 0 column, so a subset reproduces those
// columns of the whole table bit for bit (tests/shading_ltc_test.cpp).
// progress(done, total) is called after each finished column.
LtcTable fitLtcGgx(const LtcFitOptions& options, const std::vector<int>& roughnessColumns = {},
                   const std::function<void(int, int)>& progress = {});

void writeLtcTable(const std::string& path, const LtcTable& table);
LtcTable readLtcTable(const std::string& path);
// The same from bytes; `name` names them in errors.
LtcTable parseLtcTable(const std::string& bytes, const std::string& name);

// The table built into the binary (luts/ltc_ggx.lut, embedded at build time); an error if the
// build had none.
const LtcTable& builtinLtcTable();

// Per-cell report of a table: a CSV `roughness,cos_theta_v,norm,fresnel,l1_error,objective`.
std::string ltcErrorCsv(const LtcTable& table);

// What the GPU's bilinear lookup gives (texel centres, clamp to edge) for roughness r and
// cos(theta_v): layer 0 M^-1's terms, layer 1 `terms`. For CPU uses and tests.
glm::vec4 ltcLookup(const LtcTable& table, int layer, float roughness, float cosThetaV);

// The fitted lobe of cell (a, t) evaluated in its local frame (v in the xz plane, n = z), and the
// true lobe: for tests and the report.
double ltcCellLobe(const LtcTable& table, int a, int t, const glm::dvec3& l);
double ggxCellLobe(int size, int a, int t, const glm::dvec3& l);
glm::dvec3 ltcCellView(int size, int t);

}  // namespace penumbra::shading
