#include "techniques/dcs/edge_lut.h"

#include <algorithm>
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

namespace penumbra::dcs {
namespace {

constexpr double kTwoPi = 6.283185307179586;
// Format 2: the checksum covers the header's lines too (core/table_file.h; format 1's covered
// the payload only: an edited `extent` passed it and changed dcs-lut's visibility by up to 0.5).
constexpr const char* kMagic = "penumbra-edge-lut 2";

// Angle of (x, y) around the origin in [0, 2 pi), from the +x axis.
double angleOf(double x, double y) {
  double a = std::atan2(y, x);
  return a < 0.0 ? a + kTwoPi : a;
}

// The direction of cube-map texel (s, t) of `face` (OpenGL 4.5 table 8.19 inverted, |ma| = 1).
glm::dvec3 cubeDirection(int face, double sc, double tc) {
  switch (face) {
    case 0:
      return {1.0, -tc, -sc};
    case 1:
      return {-1.0, -tc, sc};
    case 2:
      return {sc, 1.0, tc};
    case 3:
      return {sc, -1.0, -tc};
    case 4:
      return {sc, -tc, 1.0};
    default:
      return {-sc, -tc, -1.0};
  }
}

// The payload in file order: the sector table, the line table, the packed positions.
std::vector<std::pair<const void*, std::size_t>> payloadOf(const EdgeLut& l) {
  return {{l.sector.data(), l.sector.size() * 4},
          {l.line.data(), l.line.size() * 4},
          {l.packed.data(), l.packed.size() * 4}};
}

}  // namespace

bool edgeLutSupports(const Light& light) { return light.shape == LightShape::Rect || light.shape == LightShape::Disk; }

Light unitLight(LightShape shape) {
  PENUMBRA_CHECK(shape == LightShape::Rect || shape == LightShape::Disk, "unitLight: rect or disk");
  Light l;
  l.name = shape == LightShape::Rect ? "rect" : "disk";
  l.shape = shape;
  l.position = glm::vec3(0.0f);
  l.size = shape == LightShape::Rect ? glm::vec2(2.0f) : glm::vec2(1.0f);
  return l;
}

std::vector<glm::vec2> normalisedSamples(const LightSampleSet& s) {
  PENUMBRA_CHECK(s.shape == LightShape::Rect || s.shape == LightShape::Disk,
                 "normalisedSamples: rect or disk sets only");
  std::vector<glm::vec2> out;
  out.reserve(s.uv.size());
  for (const glm::vec2& uv : s.uv) out.push_back(2.0f * uv - 1.0f);
  return out;
}

std::uint64_t patternHash(const std::vector<glm::vec2>& normalised, int samples, int sets) {
  Fnv1a f;
  f.value(std::int32_t(samples));
  f.value(std::int32_t(sets));
  for (const glm::vec2& p : normalised) {
    std::uint32_t x, y;
    std::memcpy(&x, &p.x, 4);
    std::memcpy(&y, &p.y, 4);
    f.value(x);
    f.value(y);
  }
  return f.h;
}

EdgeLut buildEdgeLut(const std::vector<glm::vec2>& normalised, int samples, int sets, const EdgeLutSize& size) {
  PENUMBRA_CHECK(samples >= 1 && samples <= 128 && sets >= 1, "buildEdgeLut: 1..128 samples, >= 1 set");
  PENUMBRA_CHECK(normalised.size() == std::size_t(samples) * std::size_t(sets),
                 "buildEdgeLut: positions != samples x sets");
  PENUMBRA_CHECK(size.cube >= 1 && size.line >= 2 && size.line % 2 == 0, "buildEdgeLut: bad table size");
  EdgeLut l;
  l.samples = samples, l.sets = sets, l.size = size;
  l.words = (samples + 31) / 32;
  l.pattern = patternHash(normalised, samples, sets);
  double radius = 0.0;
  for (const glm::vec2& p : normalised) radius = std::max(radius, glm::length(glm::dvec2(p)));
  l.extent = float(std::max(radius, 1e-6) * 1.0001);
  const std::size_t W = std::size_t(l.words), C = std::size_t(size.cube), L = std::size_t(size.line);
  l.sector.assign(std::size_t(sets) * 6 * C * C * W, 0u);
  l.line.assign(std::size_t(sets) * L * L * W, 0u);
  l.packed.assign(std::size_t(sets) * std::size_t(packedWords(samples)), 0u);
  for (int set = 0; set < sets; ++set) {
    const glm::vec2* pos = &normalised[std::size_t(set) * samples];
    std::vector<double> angle(std::size_t(samples), -1.0);  // -1: the centre, in no sector
    for (int k = 0; k < samples; ++k)
      if (pos[k].x != 0.0f || pos[k].y != 0.0f) angle[std::size_t(k)] = angleOf(pos[k].x, pos[k].y);
    auto setBit = [&](std::uint32_t* field, int k) { field[k / 32] |= 1u << (k % 32); };
    for (int face = 0; face < 6; ++face)
      for (std::size_t y = 0; y < C; ++y)
        for (std::size_t x = 0; x < C; ++x) {
          glm::dvec3 d =
              cubeDirection(face, 2.0 * (double(x) + 0.5) / double(C) - 1.0, 2.0 * (double(y) + 0.5) / double(C) - 1.0);
          double limit = angleOf(d.x, d.y);
          std::uint32_t* field = &l.sector[(((std::size_t(set) * 6 + std::size_t(face)) * C + y) * C + x) * W];
          for (int k = 0; k < samples; ++k)
            if (angle[std::size_t(k)] >= 0.0 && angle[std::size_t(k)] < limit) setBit(field, k);
        }
    const double R = l.extent;
    for (std::size_t y = 0; y < L; ++y)
      for (std::size_t x = 0; x < L; ++x) {
        glm::dvec2 foot((2.0 * (double(x) + 0.5) / double(L) - 1.0) * R,
                        (2.0 * (double(y) + 0.5) / double(L) - 1.0) * R);
        std::uint32_t* field = &l.line[((std::size_t(set) * L + y) * L + x) * W];
        // The four texels around c: a line through (or next to) the centre; the sector decides.
        bool centre = std::abs(foot.x) < R / double(L) * 1.5 && std::abs(foot.y) < R / double(L) * 1.5;
        double ff = glm::dot(foot, foot);
        for (int k = 0; k < samples; ++k)
          if (centre || glm::dot(glm::dvec2(pos[k]), foot) > ff) setBit(field, k);
      }
    for (int k = 0; k < samples; ++k) {
      auto q = [](float v) {
        return std::uint32_t(std::clamp(std::lround((double(v) + 1.0) * 0.5 * 255.0), 0L, 255L));
      };
      std::uint32_t word = q(pos[k].x) | (q(pos[k].y) << 8);
      l.packed[std::size_t(set) * std::size_t(packedWords(samples)) + std::size_t(k / 2)] |= word << (16 * (k % 2));
    }
  }
  return l;
}

glm::vec2 unpackPosition(const EdgeLut& l, int set, int k) {
  std::uint32_t word =
      l.packed[std::size_t(set) * std::size_t(packedWords(l.samples)) + std::size_t(k / 2)] >> (16 * (k % 2));
  return {float(word & 255u) / 255.0f * 2.0f - 1.0f, float((word >> 8) & 255u) / 255.0f * 2.0f - 1.0f};
}

std::string edgeLutFileName(const LightSampleSet& s) {
  std::string name = fmt::format("edge_{}_{}_{}_n{}_seed{}", s.shape == LightShape::Disk ? "disk" : "rect",
                                 toString(s.strategy), toString(s.pattern), s.count, s.seed);
  if (s.pattern == PixelPattern::Interleaved) name += fmt::format("_k{}", s.interleaveK);
  if (s.pattern == PixelPattern::Decorrelated) name += fmt::format("_m{}", s.setCount);
  return name + ".lut";
}

void writeEdgeLut(const std::string& path, const EdgeLut& l) {
  const std::string covered = tableHeaderLines(kMagic, {{"samples", std::to_string(l.samples)},
                                                        {"sets", std::to_string(l.sets)},
                                                        {"words", std::to_string(l.words)},
                                                        {"cube", std::to_string(l.size.cube)},
                                                        {"line", std::to_string(l.size.line)},
                                                        {"extent", fmt::format("{:.9g}", l.extent)},
                                                        {"pattern", hex64(l.pattern)}});
  writeAtomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path, std::string("cannot write: ") + std::strerror(errno));
    out << tableHeader(covered, payloadOf(l));
    // The payload in little-endian order (this code runs on little-endian machines only).
    static_assert(sizeof(std::uint32_t) == 4);
    for (const auto& [data, size] : payloadOf(l)) out.write(static_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (out.fail()) throw Error(path, "cannot write: write failed");
  });
}

EdgeLut readEdgeLut(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, std::string("cannot open: ") + std::strerror(errno));
  const TableHeader h =
      readTableHeader(in, path, kMagic, {"samples", "sets", "words", "cube", "line", "extent", "pattern"});
  EdgeLut l;
  l.samples = h.get<int>("samples");
  l.sets = h.get<int>("sets");
  l.words = h.get<int>("words");
  l.size.cube = h.get<int>("cube");
  l.size.line = h.get<int>("line");
  l.extent = h.get<float>("extent");
  if (l.samples < 1 || l.samples > 128 || l.sets < 1 || l.sets > 4096 || l.words != (l.samples + 31) / 32 ||
      l.size.cube < 1 || l.size.cube > 1024 || l.size.line < 2 || l.size.line > 4096 || !(l.extent > 0.0f))
    throw Error(path, "header values out of range");
  try {
    l.pattern = std::stoull(h.values.at("pattern"), nullptr, 16);
  } catch (const std::exception&) {
    throw Error(path, "bad pattern hash");
  }
  const std::size_t W = std::size_t(l.words), C = std::size_t(l.size.cube), L = std::size_t(l.size.line);
  const std::size_t S = std::size_t(l.sets);
  const std::size_t total = (S * 6 * C * C * W + S * L * L * W + S * std::size_t(packedWords(l.samples))) * 4;
  // Check the size before allocating: a header must not make us allocate what the file lacks.
  const auto here = in.tellg();
  in.seekg(0, std::ios::end);
  const auto end = in.tellg();
  if (here < 0 || end < 0 || std::size_t(end - here) != total)
    throw Error(path, fmt::format("payload is {} bytes, the header needs {}", std::int64_t(end - here), total));
  in.seekg(here);
  l.sector.resize(S * 6 * C * C * W);
  l.line.resize(S * L * L * W);
  l.packed.resize(S * std::size_t(packedWords(l.samples)));
  for (auto* v : {&l.sector, &l.line, &l.packed})
    in.read(reinterpret_cast<char*>(v->data()), std::streamsize(v->size() * 4));
  if (!in) throw Error(path, "truncated payload");
  h.checkChecksum(payloadOf(l));
  return l;
}

void checkEdgeLutMatches(const EdgeLut& l, const std::string& path, const std::vector<glm::vec2>& normalised,
                         int samples, int sets) {
  if (l.samples != samples || l.sets != sets)
    throw Error(path, fmt::format("edge LUT for {} samples x {} sets, the renderer uses {} x {}", l.samples, l.sets,
                                  samples, sets));
  if (l.pattern != patternHash(normalised, samples, sets))
    throw Error(path, "edge LUT was built for another sample pattern (pattern hash " + hex64(l.pattern) + " != " +
                          hex64(patternHash(normalised, samples, sets)) + "); regenerate it with `penumbra lut`");
}

}  // namespace penumbra::dcs
