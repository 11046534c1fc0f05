// The dcs edge LUT files (src/techniques/dcs/edge_lut.h): the checked-in tables are exactly what
// a fresh build gives, files round-trip, and corrupt or foreign tables are refused. No GL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "sampling/light_samples.h"
#include "techniques/dcs/edge_lut.h"

namespace penumbra::dcs {
namespace {

std::string lutDir() { return std::string(PENUMBRA_SOURCE_DIR) + "/luts"; }

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The sample set `penumbra lut` makes for a light of `shape` (a 2 x 2 rect or a unit disk).
LightSampleSet unitSamples(LightShape shape, int count, std::uint32_t seed = 1) {
  Scene scene;
  scene.lights.push_back(unitLight(shape));
  SamplingParams p;
  p.count = count;
  p.seed = seed;
  return makeLightSamples(scene, scene.lights[0], p);
}

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("penumbra_test_" + name)).string();
}

TEST(DcsEdgeLut, CheckedInTablesAreReproducedExactly) {
  int checked = 0;
  for (auto [shape, n] : {std::pair{LightShape::Rect, 16}, {LightShape::Rect, 64}, {LightShape::Disk, 16}}) {
    LightSampleSet s = unitSamples(shape, n);
    std::string name = edgeLutFileName(s);
    std::string path = lutDir() + "/" + name;
    ASSERT_TRUE(std::filesystem::exists(path)) << path << " (write it with `penumbra lut`)";
    std::string fresh = tempPath(name);
    writeEdgeLut(fresh, buildEdgeLut(normalisedSamples(s), s.count, s.setCount));
    EXPECT_EQ(readBytes(fresh), readBytes(path)) << name << " differs from a fresh build";
    std::filesystem::remove(fresh);
    ++checked;
  }
  EXPECT_EQ(checked, 3);
}

TEST(DcsEdgeLut, SamePatternOnAnyLightGivesTheSameTable) {
  // The tables live in the light's normalised frame: a large, moved, rotated light of the same
  // pattern has the same hash.
  Scene scene;
  Light l;
  l.shape = LightShape::Rect;
  l.position = {3.0f, 7.5f, -2.0f};
  l.normal = glm::normalize(glm::vec3(0.3f, -1.0f, 0.1f));
  l.tangent = glm::normalize(glm::cross(glm::vec3(0, 0, 1), l.normal));
  l.size = {5.0f, 0.7f};
  scene.lights.push_back(l);
  SamplingParams p;
  p.count = 16;
  LightSampleSet moved = makeLightSamples(scene, l, p), unit = unitSamples(LightShape::Rect, 16);
  EXPECT_EQ(patternHash(normalisedSamples(moved), 16, 1), patternHash(normalisedSamples(unit), 16, 1));
  EXPECT_EQ(edgeLutFileName(moved), edgeLutFileName(unit));
}

TEST(DcsEdgeLut, TablesHoldTheirDefinition) {
  LightSampleSet s = unitSamples(LightShape::Rect, 32);
  auto pos = normalisedSamples(s);
  EdgeLut l = buildEdgeLut(pos, 32, 1, {8, 16});
  ASSERT_EQ(l.words, 1);
  // Line texel (x, y): samples beyond the line through foot f perpendicular to f.
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      glm::vec2 f((2.0f * (x + 0.5f) / 16.0f - 1.0f) * l.extent, (2.0f * (y + 0.5f) / 16.0f - 1.0f) * l.extent);
      bool centre = std::abs(f.x) < l.extent / 16.0f * 1.5f && std::abs(f.y) < l.extent / 16.0f * 1.5f;
      for (int k = 0; k < 32; ++k) {
        bool beyond = centre || glm::dot(pos[std::size_t(k)], f) > glm::dot(f, f) * (1.0f + 1e-6f);
        bool clear = !centre && glm::dot(pos[std::size_t(k)], f) < glm::dot(f, f) * (1.0f - 1e-6f);
        bool bit = (l.line[std::size_t(y * 16 + x)] >> k) & 1u;
        if (beyond) {
          EXPECT_TRUE(bit) << x << "," << y << " sample " << k;
        }
        if (clear) {
          EXPECT_FALSE(bit) << x << "," << y << " sample " << k;
        }
      }
    }
  // Sector texel: the samples whose angle from +x is below the texel's, i.e. a prefix of the
  // samples sorted by angle; over all texels, every prefix length up to all 32 occurs.
  std::vector<int> byAngle(32);
  for (int k = 0; k < 32; ++k) byAngle[std::size_t(k)] = k;
  auto angle = [&](int k) {
    float a = std::atan2(pos[std::size_t(k)].y, pos[std::size_t(k)].x);
    return a < 0.0f ? a + 6.2831853f : a;
  };
  std::sort(byAngle.begin(), byAngle.end(), [&](int a, int b) { return angle(a) < angle(b); });
  std::vector<bool> lengths(33, false);
  for (std::uint32_t field : l.sector) {
    int n = __builtin_popcount(field);
    std::uint32_t prefix = 0;
    for (int i = 0; i < n; ++i) prefix |= 1u << byAngle[std::size_t(i)];
    EXPECT_EQ(field, prefix);
    lengths[std::size_t(n)] = true;
  }
  // 8 x 8 faces: about 32 angular steps; the first and last hold (nearly) none and all.
  auto first = std::find(lengths.begin(), lengths.end(), true) - lengths.begin();
  auto last = lengths.rend() - std::find(lengths.rbegin(), lengths.rend(), true) - 1;
  EXPECT_LE(first, 2);
  EXPECT_GE(last, 30);
  // Packed positions decode to within half an 8-bit step.
  for (int k = 0; k < 32; ++k) {
    glm::vec2 d = unpackPosition(l, 0, k) - pos[std::size_t(k)];
    EXPECT_LE(std::max(std::abs(d.x), std::abs(d.y)), 1.0f / 255.0f + 1e-6f);
  }
}

TEST(DcsEdgeLut, FilesRoundTrip) {
  LightSampleSet s = unitSamples(LightShape::Disk, 40);
  EdgeLut l = buildEdgeLut(normalisedSamples(s), 40, 1, {4, 8});
  std::string path = tempPath("roundtrip.lut");
  writeEdgeLut(path, l);
  EdgeLut r = readEdgeLut(path);
  EXPECT_EQ(r.samples, 40);
  EXPECT_EQ(r.words, 2);
  EXPECT_EQ(r.pattern, l.pattern);
  EXPECT_EQ(r.extent, l.extent);
  EXPECT_EQ(r.sector, l.sector);
  EXPECT_EQ(r.line, l.line);
  EXPECT_EQ(r.packed, l.packed);
  std::filesystem::remove(path);
}

void expectError(const std::function<void()>& f, const std::string& where, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "no error; expected " << what;
  } catch (const Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(where), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
  }
}

TEST(DcsEdgeLut, ForeignCorruptAndTruncatedTablesAreRefused) {
  LightSampleSet s16 = unitSamples(LightShape::Rect, 16), other = unitSamples(LightShape::Rect, 16, 2);
  std::string path = lutDir() + "/" + edgeLutFileName(s16);
  EdgeLut l = readEdgeLut(path);
  // Built for seed 1: refused for seed 2's pattern, and for another sample count.
  expectError([&] { checkEdgeLutMatches(l, path, normalisedSamples(other), 16, 1); }, path, "another sample pattern");
  LightSampleSet s32 = unitSamples(LightShape::Rect, 32);
  expectError([&] { checkEdgeLutMatches(l, path, normalisedSamples(s32), 32, 1); }, path, "16 samples");
  checkEdgeLutMatches(l, path, normalisedSamples(s16), 16, 1);  // its own pattern: accepted

  std::string bytes = readBytes(path);
  std::string bad = tempPath("bad.lut");
  auto writeBytes = [&](const std::string& b) { std::ofstream(bad, std::ios::binary) << b; };
  writeBytes(bytes.substr(0, bytes.size() - 100));
  expectError([&] { readEdgeLut(bad); }, bad, "payload is");
  std::string flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x20;
  writeBytes(flipped);
  expectError([&] { readEdgeLut(bad); }, bad, "checksum mismatch");
  // A header edited in range (the extent scales every foot: dcs-lut's visibility off by up to
  // 0.5) fails the checksum, which covers the header since format 2.
  std::string edited = bytes;
  const std::size_t at = edited.find("\nextent ") + 8;
  edited[at] = edited[at] == '9' ? '8' : char(edited[at] + 1);
  writeBytes(edited);
  expectError([&] { readEdgeLut(bad); }, bad, "checksum mismatch");
  std::string v1 = bytes;
  v1.replace(0, v1.find('\n'), "penumbra-edge-lut 1");
  writeBytes(v1);
  expectError(
      [&] { readEdgeLut(bad); }, bad,
      "format 'penumbra-edge-lut 1', this build reads 'penumbra-edge-lut 2': regenerate it with `penumbra lut`");
  writeBytes("penumbra-edge-lut 2\nsamples 16\nsamples 16\nend\n");
  expectError([&] { readEdgeLut(bad); }, bad, "given twice");
  writeBytes("penumbra-edge-lut 2\nsamples 100000\nend\n");
  expectError([&] { readEdgeLut(bad); }, bad, "incomplete header");
  writeBytes("P6\n");
  expectError([&] { readEdgeLut(bad); }, bad, "not a penumbra-edge-lut file");
  std::filesystem::remove(bad);
  expectError([&] { readEdgeLut(bad); }, bad, "cannot open");
}

}  // namespace
}  // namespace penumbra::dcs
