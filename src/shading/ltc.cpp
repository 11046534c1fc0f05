// The LTC table's file, its embedded copy and its lookup (format in ltc.h).
#include "shading/ltc.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "core/error.h"
#include "core/files.h"
#include "core/fnv.h"
#include "core/table_file.h"

namespace penumbra::shading {

// Generated from luts/ltc_ggx.lut by cmake/embed_binary.cmake (empty where the file is missing).
extern const unsigned char kEmbeddedLtcGgx[];
extern const std::size_t kEmbeddedLtcGgxSize;

namespace {

// Format 2: the checksum covers the header's lines too (core/table_file.h; format 1's covered
// the payload only).
constexpr const char* kMagic = "penumbra-ltc-ggx 2";

// The payload in file order: M^-1, then the terms.
std::vector<std::pair<const void*, std::size_t>> payloadOf(const LtcTable& t) {
  return {{t.minv.data(), t.minv.size() * sizeof(glm::vec4)}, {t.terms.data(), t.terms.size() * sizeof(glm::vec4)}};
}

}  // namespace

void writeLtcTable(const std::string& path, const LtcTable& t) {
  writeAtomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path, std::string("cannot write: ") + std::strerror(errno));
    out << tableHeader(tableHeaderLines(kMagic, {{"size", std::to_string(t.fit.size)},
                                                 {"fit-samples", std::to_string(t.fit.fitSamples)},
                                                 {"moment-samples", std::to_string(t.fit.momentSamples)},
                                                 {"error-samples", std::to_string(t.fit.errorSamples)},
                                                 {"iterations", std::to_string(t.fit.iterations)}}),
                       payloadOf(t));
    // Little-endian float32 (this code runs on little-endian machines only).
    static_assert(sizeof(glm::vec4) == 16);
    for (const auto& [data, size] : payloadOf(t)) out.write(static_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (out.fail()) throw Error(path, "cannot write: write failed");
  });
}

LtcTable parseLtcTable(const std::string& bytes, const std::string& name) {
  std::istringstream in(bytes);
  const TableHeader h =
      readTableHeader(in, name, kMagic, {"size", "fit-samples", "moment-samples", "error-samples", "iterations"});
  LtcTable t;
  t.fit.size = h.get<int>("size");
  t.fit.fitSamples = h.get<int>("fit-samples");
  t.fit.momentSamples = h.get<int>("moment-samples");
  t.fit.errorSamples = h.get<int>("error-samples");
  t.fit.iterations = h.get<int>("iterations");
  if (t.fit.size < 2 || t.fit.size > 256) throw Error(name, "table size outside 2..256");
  t.fit.threads = 0;
  const std::size_t cells = std::size_t(t.fit.size) * std::size_t(t.fit.size);
  const std::size_t need = 2 * cells * sizeof(glm::vec4);
  const std::size_t have = bytes.size() - std::size_t(in.tellg());
  if (have != need) throw Error(name, fmt::format("payload is {} bytes, the header needs {}", have, need));
  t.minv.resize(cells);
  t.terms.resize(cells);
  std::memcpy(t.minv.data(), bytes.data() + in.tellg(), cells * sizeof(glm::vec4));
  std::memcpy(t.terms.data(), bytes.data() + std::size_t(in.tellg()) + cells * sizeof(glm::vec4),
              cells * sizeof(glm::vec4));
  h.checkChecksum(payloadOf(t));
  for (const auto* v : {&t.minv, &t.terms})
    for (const glm::vec4& x : *v)
      if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z) || !std::isfinite(x.w))
        throw Error(name, "a table value is NaN or infinite");
  return t;
}

LtcTable readLtcTable(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream s;
  s << in.rdbuf();
  return parseLtcTable(s.str(), path);
}

const LtcTable& builtinLtcTable() {
  static const LtcTable table = [] {
    if (kEmbeddedLtcGgxSize == 0)
      throw Error("luts/ltc_ggx.lut",
                  "this build has no LTC table (the file was missing at build time); "
                  "fit it with the LUT tool (luts/README.md) and rebuild");
    return parseLtcTable(std::string(reinterpret_cast<const char*>(kEmbeddedLtcGgx), kEmbeddedLtcGgxSize),
                         "luts/ltc_ggx.lut (built in)");
  }();
  return table;
}

std::string ltcErrorCsv(const LtcTable& t) {
  std::string s = "roughness,cos_theta_v,norm,fresnel,l1_error,objective\n";
  const int n = t.size();
  for (int row = 0; row < n; ++row)
    for (int a = 0; a < n; ++a) {
      const glm::vec4 e = t.terms[std::size_t(row) * std::size_t(n) + std::size_t(a)];
      s += fmt::format("{:.6f},{:.6f},{:.9g},{:.9g},{:.6g},{:.6g}\n", double(a) / (n - 1), ltcCellView(n, row).z, e.x,
                       e.y, e.z, e.w);
    }
  return s;
}

glm::vec4 ltcLookup(const LtcTable& t, int layer, float roughness, float cosThetaV) {
  const int n = t.size();
  const std::vector<glm::vec4>& v = layer == 0 ? t.minv : t.terms;
  // Grid coordinates u (N - 1): the shader looks up at texel centres, (u (N - 1) + 1/2) / N.
  auto axis = [n](float u, int& i0, float& f) {
    float x = std::clamp(u, 0.0f, 1.0f) * float(n - 1);
    i0 = std::min(int(std::floor(x)), n - 2);
    f = x - float(i0);
  };
  int a0, t0;
  float fa, ft;
  axis(roughness, a0, fa);
  axis(std::sqrt(std::max(1.0f - cosThetaV, 0.0f)), t0, ft);
  auto at = [&](int a, int row) { return v[std::size_t(row) * std::size_t(n) + std::size_t(a)]; };
  return glm::mix(glm::mix(at(a0, t0), at(a0 + 1, t0), fa), glm::mix(at(a0, t0 + 1), at(a0 + 1, t0 + 1), fa), ft);
}

}  // namespace penumbra::shading
