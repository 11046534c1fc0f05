// Compressed glTF: EXT_meshopt_compression (with KHR_mesh_quantization) and
// KHR_draco_mesh_compression decode to the meshes they were made from, within the encoders'
// quantization; corrupt streams and bad declarations are one-line errors naming the file.
//
// Files: tests/data/scene/bunny_meshopt.glb and bunny_meshopt_float.glb were made from
// scenes/models/bunny.obj with gltfpack 1.3 (npm `gltfpack`): `gltfpack -i bunny.obj -o
// bunny_meshopt.glb -c` (14-bit positions, KHR_mesh_quantization, a fallback buffer) and `... -c
// -vpf -vnf` (float positions through the EXPONENTIAL filter). scenes/models/bunny-draco.glb and
// suzanne-draco.glb are the CC0 models of npm @pmndrs/assets 1.7.0 (models/bunny.glb.js and
// suzi.glb.js, base64 decoded). The Draco engine is Debian assimp-testmodels'.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <glm/gtx/component_wise.hpp>
#include <map>
#include <unordered_map>

#include "scene/loaders.h"
#include "scene_test_util.h"

namespace penumbra {
namespace {

using test::expectError;
using test::sceneData;
using test::sourcePath;

const char* const kAssimpGltf = "/usr/share/assimp/models/glTF2";
const std::string kDracoBunny = "scenes/models/bunny-draco.glb";
const std::string kMeshoptBunny = "bunny_meshopt.glb";

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// A GLB's JSON and BIN chunks, to edit and write back.
struct Glb {
  nlohmann::json json;
  std::string bin;
};

std::uint32_t u32(const std::string& s, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

Glb readGlb(const std::string& path) {
  const std::string bytes = readFile(path);
  const std::uint32_t jsonLength = u32(bytes, 12);
  Glb g;
  g.json = nlohmann::json::parse(bytes.substr(20, jsonLength));
  const std::size_t binStart = 20 + jsonLength;
  g.bin = bytes.substr(binStart + 8, u32(bytes, binStart));
  return g;
}

std::string writeGlb(const Glb& g) {
  std::string json = g.json.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  std::string bin = g.bin;
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  std::string out = "glTF";
  auto put = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  put(2);
  put(std::uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  put(std::uint32_t(json.size()));
  put(0x4E4F534A);
  out += json;
  put(std::uint32_t(bin.size()));
  put(0x004E4942);
  return out + bin;
}

// Nearest-vertex lookup on a uniform grid of cell `cell` (queries within one cell of a vertex).
class Nearest {
 public:
  Nearest(const std::vector<glm::vec3>& points, float cell) : points_(points), cell_(cell) {
    for (std::size_t i = 0; i < points.size(); ++i) grid_[key(cellOf(points[i]))].push_back(i);
  }
  // Index of the nearest point within one cell of p, and its distance (-1 / inf when none).
  std::pair<long, double> find(glm::vec3 p) const {
    const glm::ivec3 c = cellOf(p);
    long best = -1;
    double dist = INFINITY;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = grid_.find(key(c + glm::ivec3(dx, dy, dz)));
          if (it == grid_.end()) continue;
          for (std::size_t i : it->second) {
            const double d = glm::distance(glm::dvec3(points_[i]), glm::dvec3(p));
            if (d < dist) dist = d, best = long(i);
          }
        }
    return {best, dist};
  }
  // Indices of the points within one cell's length of p.
  std::vector<std::size_t> within(glm::vec3 p) const {
    std::vector<std::size_t> out;
    const glm::ivec3 c = cellOf(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = grid_.find(key(c + glm::ivec3(dx, dy, dz)));
          if (it == grid_.end()) continue;
          for (std::size_t i : it->second)
            if (glm::distance(points_[i], p) <= cell_) out.push_back(i);
        }
    return out;
  }

 private:
  glm::ivec3 cellOf(glm::vec3 p) const { return glm::ivec3(glm::floor(p / cell_)); }
  static std::int64_t key(glm::ivec3 c) {
    return (std::int64_t(c.x) * 73856093) ^ (std::int64_t(c.y) * 19349663) ^ (std::int64_t(c.z) * 83492791);
  }
  const std::vector<glm::vec3>& points_;
  float cell_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> grid_;
};

float extentOf(const std::vector<glm::vec3>& points) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return glm::compMax(hi - lo);
}

// How `decoded` matches `original`: the farthest a decoded vertex lies from its nearest original
// vertex, and how many of decoded's triangles have no original triangle whose corners (in the
// same cyclic order) each lie within `tolerance` of theirs.
struct Match {
  double farthest = 0;
  std::size_t trianglesMissing = 0;
};
Match match(const geo::TriangleMesh& decoded, const geo::TriangleMesh& original, float tolerance) {
  const Nearest nearest(original.positions, tolerance);
  std::vector<std::vector<std::uint32_t>> incident(original.positions.size());
  for (std::uint32_t t = 0; t < original.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) incident[original.triangles[t][c]].push_back(t);
  Match m;
  for (const glm::vec3& p : decoded.positions) m.farthest = std::max(m.farthest, nearest.find(p).second);
  auto close = [&](glm::vec3 a, glm::vec3 b) { return glm::distance(a, b) <= tolerance; };
  for (const glm::uvec3& t : decoded.triangles) {
    const glm::vec3 a = decoded.positions[t.x], b = decoded.positions[t.y], c = decoded.positions[t.z];
    bool found = false;
    for (std::size_t v : nearest.within(a))
      for (std::uint32_t o : incident[v]) {
        const glm::uvec3 u = original.triangles[o];
        for (int r = 0; r < 3 && !found; ++r)
          found = close(a, original.positions[u[r]]) && close(b, original.positions[u[(r + 1) % 3]]) &&
                  close(c, original.positions[u[(r + 2) % 3]]);
      }
    m.trianglesMissing += found ? 0 : 1;
  }
  return m;
}

// Every primitive's vertices in the file's space, one mesh per primitive instance.
geo::TriangleMesh only(const detail::Model& m) {
  EXPECT_EQ(m.meshes.size(), 1u);
  return m.meshes.empty() ? geo::TriangleMesh{} : m.meshes[0].mesh;
}

TEST(Compressed, MeshoptBunnyHasTheObjsTriangles) {
  const geo::TriangleMesh obj = only(detail::loadObjModel(sourcePath("scenes/models/bunny.obj")));
  const float extent = extentOf(obj.positions);
  // gltfpack's default 14-bit positions on the mesh's largest side; with -vpf as floats through
  // the exponential filter, with the same 14 bits of mantissa.
  for (const auto& [file, bits] :
       std::vector<std::pair<std::string, int>>{{"bunny_meshopt.glb", 14}, {"bunny_meshopt_float.glb", 14}}) {
    SCOPED_TRACE(file);
    const detail::Model model = detail::loadGltf(sceneData(file));
    const geo::TriangleMesh packed = only(model);
    EXPECT_EQ(packed.triangles.size(), obj.triangles.size());
    const double step = extent / double((1 << bits) - 1);
    const Match m = match(packed, obj, float(step));
    std::printf("%s: farthest vertex %.3g of the bunny's %.3g (step %.3g), %zu triangles unmatched\n", file.c_str(),
                m.farthest, double(extent), step, m.trianglesMissing);
    EXPECT_LE(m.farthest, step) << "positions beyond the quantization";
    EXPECT_EQ(m.trianglesMissing, 0u);
  }
}

TEST(Compressed, DracoEngineIsTheUncompressedWithinItsQuantization) {
  const std::string dir = kAssimpGltf;
  if (!std::filesystem::is_directory(dir)) FAIL() << "assimp-testmodels not installed (./setup.sh --deps installs it)";
  const detail::Model draco = detail::loadGltf(dir + "/draco/2CylinderEngine.gltf");
  const detail::Model plain = detail::loadGltf(dir + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  ASSERT_EQ(draco.meshes.size(), plain.meshes.size());
  std::size_t trianglesDraco = 0, trianglesPlain = 0, missing = 0;
  double worst = 0;  // the farthest vertex, in steps of 2^-11 of its mesh's extent
  for (std::size_t i = 0; i < draco.meshes.size(); ++i) {
    const geo::TriangleMesh& d = draco.meshes[i].mesh;
    const geo::TriangleMesh& p = plain.meshes[i].mesh;
    ASSERT_EQ(draco.meshes[i].name.substr(draco.meshes[i].name.find('#')),
              plain.meshes[i].name.substr(plain.meshes[i].name.find('#')));
    const float extent = extentOf(p.positions);
    const Match m = match(d, p, 1.5f * extent / 2047.0f);
    worst = std::max(worst, m.farthest / (extent / 2047.0));
    trianglesDraco += d.triangles.size();
    trianglesPlain += p.triangles.size();
    missing += m.trianglesMissing;
  }
  std::printf(
      "draco engine: %zu triangles (uncompressed %zu), %zu without a counterpart within 1.5 steps; farthest vertex "
      "%.2f "
      "steps of 2^-11 of its mesh\n",
      trianglesDraco, trianglesPlain, missing, worst);
  // The encoder dropped the file's repeated-index triangles (the loader drops them from the
  // uncompressed file too); its 11-bit quantization of positions (a vertex moves up to sqrt(3)/2
  // of a step of the mesh's local extent; measured 0.94 of a step of its placed extent) makes
  // 17 thin triangles degenerate.
  EXPECT_LE(trianglesPlain - trianglesDraco, trianglesPlain / 1000);
  EXPECT_EQ(missing, 0u);
  EXPECT_LE(worst, 1.5);
}

TEST(Compressed, CC0ModelsLoad) {
  for (const auto& [file, triangles] : std::vector<std::pair<std::string, std::size_t>>{
           {"scenes/models/bunny-draco.glb", 5648}, {"scenes/models/suzanne-draco.glb", 14842}}) {
    SCOPED_TRACE(file);
    const detail::Model m = detail::loadGltf(sourcePath(file));
    const geo::TriangleMesh mesh = only(m);
    EXPECT_EQ(mesh.triangles.size(), triangles);
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
    std::printf("%s: volume %.4f\n", file.c_str(), test::signedVolume(mesh));
    EXPECT_GT(test::signedVolume(mesh), 0.1) << "wound outward, enclosing volume";
  }
}

// One edit of a compressed file and the error it must give.
struct BadEdit {
  const char* name;
  std::string file;
  std::function<void(Glb&)> edit;
  const char* message;
};

TEST(Compressed, BadDeclarationsAreOneLineErrors) {
  const std::vector<BadEdit> edits = {
      {"meshopt count beyond its bufferView", kMeshoptBunny,
       [](Glb& g) { g.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 100000; },
       "do not fit in the bufferView"},
      {"meshopt mode unknown", kMeshoptBunny,
       [](Glb& g) { g.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["mode"] = "QUADS"; },
       "unknown mode 'QUADS'"},
      {"meshopt stride not a multiple of 4", kMeshoptBunny,
       [](Glb& g) { g.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 6; },
       "not a multiple of 4"},
      {"meshopt stream past its buffer", kMeshoptBunny,
       [](Glb& g) { g.json["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 100000; },
       "overruns buffer 0"},
      {"meshopt stream truncated", kMeshoptBunny,
       [](Glb& g) { g.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 100; },
       "bufferView 0 (EXT_meshopt_compression): the ATTRIBUTES stream does not decode"},
      {"meshopt filter on indices", kMeshoptBunny,
       [](Glb& g) { g.json["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["filter"] = "OCTAHEDRAL"; },
       "filter OCTAHEDRAL on a TRIANGLES stream"},
      {"plain view in the fallback buffer", kMeshoptBunny, [](Glb& g) { g.json["bufferViews"][0].erase("extensions"); },
       "fallback buffer, without data"},
      {"draco vertex count other than POSITION's", kDracoBunny, [](Glb& g) { g.json["accessors"][1]["count"] = 2825; },
       "vertices but POSITION declares 2825"},
      {"draco index count other than declared", kDracoBunny, [](Glb& g) { g.json["accessors"][0]["count"] = 30; },
       "the indices accessor declares 30 indices"},
      {"draco attribute not in the stream", kDracoBunny,
       [](Glb& g) {
         g.json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 7;
       },
       "NORMAL's attribute 7 is not in the stream"},
      {"draco stream not a stream", kDracoBunny, [](Glb& g) { std::fill(g.bin.begin(), g.bin.begin() + 64, 'x'); },
       "(KHR_draco_mesh_compression): not a Draco"},
  };
  test::TempDir dir;
  for (const BadEdit& e : edits) {
    SCOPED_TRACE(e.name);
    Glb g = readGlb(e.file == kDracoBunny ? sourcePath(e.file) : sceneData(e.file));
    e.edit(g);
    const std::string path = dir.file("edited.glb", writeGlb(g));
    expectError([&] { detail::loadGltf(path); }, path, e.message);
  }
}

// Corrupt streams: bytes of the compressed data changed or the file cut; each load succeeds or
// throws one penumbra::Error naming the file (under ASan/UBSan: never a read out of bounds).
TEST(Compressed, CorruptStreamsNeverCrash) {
  test::TempDir dir;
  std::uint32_t state = 777;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  };
  int loaded = 0, rejected = 0;
  for (const std::string& file : {sceneData("bunny_meshopt.glb"), sceneData("bunny_meshopt_float.glb"),
                                  sourcePath("scenes/models/bunny-draco.glb")}) {
    const Glb original = readGlb(file);
    for (int round = 0; round < 60; ++round) {
      Glb g = original;
      const int edits = 1 + int(next() % 8);
      for (int e = 0; e < edits; ++e) g.bin[next() % g.bin.size()] = char(next() & 0xff);
      std::string bytes = writeGlb(g);
      if (round % 10 == 9) bytes.erase(bytes.end() - std::ptrdiff_t(4 * (1 + next() % 64)), bytes.end());
      const std::string path = dir.file("m.glb", bytes);
      try {
        detail::loadGltf(path);
        ++loaded;
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        ++rejected;
      } catch (const std::exception& e) {
        ADD_FAILURE() << file << " round " << round << ": " << e.what();
      }
    }
  }
  std::printf("corrupt compressed streams: %d loaded, %d rejected\n", loaded, rejected);
  EXPECT_GT(rejected, 0);
}

}  // namespace
}  // namespace penumbra
