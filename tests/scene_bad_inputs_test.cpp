// The bad inputs of hard-cases.md ("Bad inputs: expected behaviour") that the format-specific
// tests (scene_gltf_test, scene_json_test, geometry_io_test, core_image_io_test, cli_test.sh)
// do not already cover, each through loadScene as a user would reach it. Every malformed file
// is generated here from a valid one, so the data folder stays small. Expected everywhere: one
// penumbra::Error line naming the file and the problem, or a load whose warnings and mesh
// reports count what was dropped or changed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/image_io.h"
#include "scene/loaders.h"
#include "scene_test_util.h"

namespace penumbra {
namespace {

using detail::Json;
using test::base64;
using test::cubeDocument;
using test::expectError;
using test::hasWarning;
using test::sceneData;
using test::sceneWithTexture;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

struct CubeBuffer {
  float positions[8][3];
  std::uint16_t indices[36];
};

CubeBuffer cubeBuffer(const Json& doc) {
  const std::string uri = doc["buffers"][0]["uri"];
  std::string bytes;
  {  // decode the data URI: the test owns both sides, so a plain decoder suffices
    const std::string b64 = uri.substr(uri.find(',') + 1);
    auto value = [](char c) {
      return c >= 'A' && c <= 'Z'   ? c - 'A'
             : c >= 'a' && c <= 'z' ? c - 'a' + 26
             : c >= '0' && c <= '9' ? c - '0' + 52
             : c == '+'             ? 62
                                    : 63;
    };
    std::uint32_t bits = 0;
    int count = 0;
    for (char c : b64) {
      if (c == '=') break;
      bits = bits << 6 | std::uint32_t(value(c));
      if ((count += 6) >= 8) bytes += char((bits >> (count -= 8)) & 0xff);
    }
  }
  CubeBuffer b;
  EXPECT_EQ(bytes.size(), sizeof(b));
  std::memcpy(&b, bytes.data(), sizeof(b));
  return b;
}

void setCubeBuffer(Json& doc, const CubeBuffer& b) {
  const std::string bytes(reinterpret_cast<const char*>(&b), sizeof(b));
  doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bytes);
}

// Triangles of the cube that use vertex v.
std::size_t trianglesUsing(const CubeBuffer& b, std::uint16_t v) {
  std::size_t n = 0;
  for (int t = 0; t < 12; ++t) n += (b.indices[3 * t] == v || b.indices[3 * t + 1] == v || b.indices[3 * t + 2] == v);
  return n;
}

std::size_t dropped(const Scene& s, std::size_t geo::MeshReport::*count) {
  std::size_t n = 0;
  for (const SceneMesh& m : s.meshes) n += m.report.*count;
  return n;
}

// ---------------------------------------------------------------------------------------------
// glTF (hard-cases.md: "Missing POSITION, NaN/Inf positions (dropped with a count), huge
// magnitudes (warned)"; "singular or NaN matrices"; "Declared sizes far larger than the payload:
// reject before allocating"; URIs of images; primitive modes).

TEST(SceneBadInputs, GltfNanPositionsAreDroppedWithACount) {
  test::TempDir dir;
  Json doc = cubeDocument();
  CubeBuffer b = cubeBuffer(doc);
  b.positions[0][1] = kNaN;
  setCubeBuffer(doc, b);
  const std::string path = dir.file("nan.gltf", doc.dump());
  const std::size_t expected = trianglesUsing(b, 0);
  ASSERT_GT(expected, 0u);
  const Scene s = loadScene(path);
  EXPECT_EQ(dropped(s, &geo::MeshReport::droppedNonFinite), expected);
  // 12 cube triangles less the dropped ones, plus the 2 of the bare file's floor.
  EXPECT_EQ(s.triangleCount(), 12 - expected + 2);
  EXPECT_TRUE(hasWarning(s, path + ": triangles dropped in 1 of 1 primitives: " + std::to_string(expected) +
                                " with non-finite positions"));
}

TEST(SceneBadInputs, GltfOnlyNanPositionsIsAnErrorWithTheCount) {
  test::TempDir dir;
  Json doc = cubeDocument();
  CubeBuffer b = cubeBuffer(doc);
  for (auto& p : b.positions) p[0] = kNaN;
  setCubeBuffer(doc, b);
  const std::string path = dir.file("all_nan.gltf", doc.dump());
  expectError([&] { loadScene(path); }, path,
              "no triangles to load (triangles dropped: 12 with "
              "non-finite positions)");
}

TEST(SceneBadInputs, GltfHugeMagnitudesAreKeptAndWarned) {
  test::TempDir dir;
  Json doc = cubeDocument();
  CubeBuffer b = cubeBuffer(doc);
  b.positions[7][0] = 3e7f;
  setCubeBuffer(doc, b);
  const std::string path = dir.file("huge.gltf", doc.dump());
  const Scene s = loadScene(path);
  EXPECT_EQ(s.triangleCount(), 12u + 2u);
  ASSERT_EQ(s.meshes.size(), 2u);  // the file's mesh and the bare-file floor under it
  EXPECT_EQ(s.meshes[0].report.hugeCoordinates, 1u);
  EXPECT_TRUE(hasWarning(s, "1 vertices with coordinates beyond 1e6 (kept"));
}

TEST(SceneBadInputs, GltfMissingPositionIsCountedWhenNothingIsLeft) {
  test::TempDir dir;
  Json doc = cubeDocument();
  doc["meshes"][0]["primitives"][0]["attributes"] = Json::object({{"NORMAL", 0}});
  const std::string path = dir.file("no_position.gltf", doc.dump());
  expectError([&] { loadScene(path); }, path,
              "1 primitives without triangles (points, lines, "
              "no POSITION or sparse)");
}

TEST(SceneBadInputs, GltfNonFiniteNodeTransformsDropTheNodeWithAWarning) {
  test::TempDir dir;
  // A zero quaternion has no rotation (NaN once normalised). Nodes 2 and 3 each scale x by
  // 1e30, which a float holds, but node 3's world matrix (1e60) does not. Node 0 stays as the
  // one valid instance.
  Json doc = cubeDocument();
  doc["nodes"] = Json::parse(R"([{"mesh":0,"children":[1,2]},
                                 {"mesh":0,"rotation":[0,0,0,0]},
                                 {"scale":[1e30,1,1],"children":[3]},
                                 {"mesh":0,"scale":[1e30,1,1]}])");
  const std::string path = dir.file("nan_nodes.gltf", doc.dump());
  const detail::Model m = detail::loadGltf(path);
  EXPECT_EQ(m.meshes.size(), 1u);
  for (const char* node : {"node 1: singular or non-finite transform; node and its children dropped",
                           "node 3: singular or non-finite transform"}) {
    bool warned = false;
    for (const std::string& w : m.warnings) warned = warned || w.find(node) != std::string::npos;
    EXPECT_TRUE(warned) << node;
  }
  EXPECT_EQ(m.warnings.size(), 2u) << ::testing::PrintToString(m.warnings);
  EXPECT_EQ(loadScene(path).triangleCount(), 12u + 2u);
}

// A finite transform can still take a huge coordinate beyond float range: the triangles are
// dropped and counted (found by fuzzing, tests/fuzz/regressions/).
TEST(SceneBadInputs, TransformsOverflowingCoordinatesDropAndCountTheTriangles) {
  test::TempDir dir;
  Json doc = cubeDocument();
  CubeBuffer b = cubeBuffer(doc);
  b.positions[7][0] = 1e10f;
  setCubeBuffer(doc, b);
  doc["nodes"][0]["scale"] = Json::array({1e30, 1, 1});
  const std::string path = dir.file("overflow.gltf", doc.dump());
  const std::size_t expected = trianglesUsing(b, 7);
  const detail::Model m = detail::loadGltf(path);
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_EQ(m.meshes[0].report.droppedNonFinite, expected);
  EXPECT_EQ(m.meshes[0].mesh.triangles.size(), 12 - expected);
  bool warned = false;
  for (const std::string& w : m.warnings)
    warned = warned || w.find("node 0: " + std::to_string(expected) +
                              " triangles of overflow.gltf#cube dropped: the node's transform "
                              "takes them beyond float range") != std::string::npos;
  EXPECT_TRUE(warned) << ::testing::PrintToString(m.warnings);

  // The same from a scene file: 3e38 * 1 + 3e38 overflows for the vertices at x = 1.
  dir.file("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\n");
  const std::string scene =
      dir.file("scene.json", R"({"objects": [{"file": "tri.obj", "scale": [3e38, 1, 1], "translate": [3e38, 0, 0]}],
                        "lights": [{"position": [0, 2, 0]}],
                        "camera": {"position": [0, 0, 5], "target": [0, 0, 0]}})");
  const Scene s = loadScene(scene);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].report.droppedNonFinite, 1u);
  EXPECT_EQ(s.triangleCount(), 1u);
  EXPECT_TRUE(hasWarning(s, scene + ": objects[0]: 1 triangles of " + dir.path() +
                                "/tri.obj dropped: the transform takes them beyond float range"));
  // Without a camera, bounds this large cannot be framed: a clear error, not an Inf camera.
  const std::string unframed = dir.file("unframed.json", R"({"objects": [{"file": "tri.obj", "scale": [3e38, 1, 1],
                                        "translate": [3e38, 0, 0]}]})");
  expectError([&] { loadScene(unframed); }, unframed,
              "camera: the scene's bounds are too large to frame automatically");
}

TEST(SceneBadInputs, GltfHugeAccessorCountIsRejectedBeforeAllocating) {
  test::TempDir dir;
  Json doc = cubeDocument();
  doc["accessors"][0]["count"] = 1000000000;
  const std::string path = dir.file("huge_count.gltf", doc.dump());
  expectError([&] { loadScene(path); }, path,
              "accessor 0 (huge_count.gltf#cube POSITION): needs 12000000000 bytes (offset 0, "
              "stride 12, count 1000000000) but bufferView 0 has 96");
  doc = cubeDocument();
  doc["accessors"][1]["count"] = 4000000000u;  // indices: needs 8 GB
  const std::string indices = dir.file("huge_index_count.gltf", doc.dump());
  expectError([&] { loadScene(indices); }, indices,
              "accessor 1 (huge_index_count.gltf#cube indices): needs 8000000000 bytes");
}

TEST(SceneBadInputs, GltfBufferLongerThanItsDataUriIsRejected) {
  test::TempDir dir;
  Json doc = cubeDocument();
  doc["buffers"][0]["byteLength"] = 1000000000;
  const std::string path = dir.file("long_buffer.gltf", doc.dump());
  expectError([&] { loadScene(path); }, path, "buffer 0 declares 1000000000 bytes but its data URI holds 168");
}

TEST(SceneBadInputs, GltfImageUrisAreSandboxedLikeBuffers) {
  test::TempDir dir;
  dir.file("secret.png", "never read");
  // {uri, the expected problem}: external URIs are quoted in the message, data: URIs are not.
  const char* const kBad[][2] = {{"../secret.png", "uri '../secret.png' leaves its folder ('..')"},
                                 {"/etc/passwd", "uri '/etc/passwd' is an absolute path"},
                                 {"http://example.com/a.png", "is a URI with scheme 'http:', not a relative path"},
                                 {"file:///etc/passwd", "is a URI with scheme 'file:', not a relative path"},
                                 {"a.png;rm -rf x", "uri 'a.png;rm -rf x' contains the shell metacharacter ';'"},
                                 {"data:image/png;base64,@@@@", "data URI is not valid base64"},
                                 {"data:text/html,<b>", "unsupported data URI 'data:text/html'"}};
  for (const auto& [uri, problem] : kBad) {
    SCOPED_TRACE(uri);
    Json doc = cubeDocument();
    doc["images"] = Json::array({Json::object({{"uri", uri}})});
    const std::string path = dir.file("inner/image.gltf", doc.dump());
    expectError([&] { loadScene(path); }, path, problem);
    expectError([&] { loadScene(path); }, path, "image 0: ");
  }
}

// ---------------------------------------------------------------------------------------------
// OBJ / PLY / OFF / STL (hard-cases.md: "out-of-range or repeated face indices, ... headers
// claiming 10^9 vertices, NaN vertices: every dropped/duplicated face counted and reported,
// never silently lost").

// Five faces over four vertices, vertex 3 NaN: one good face, then one face each with an index
// out of range, a repeated index, the NaN vertex, and the good face again (rotated).
struct MeshCase {
  const char* name;
  std::string (*write)();
};

std::string plyHeader(const char* format, const char* indexType) {
  return std::string("ply\nformat ") + format +
         " 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 5\nproperty list uchar " +
         indexType + " vertex_indices\nend_header\n";
}

const int kFaces[5][3] = {{0, 1, 2}, {0, 1, 9}, {0, 0, 1}, {0, 1, 3}, {1, 2, 0}};
const char* const kVertexText[4] = {"0 0 0", "1 0 0", "0 1 0", "nan 0 1"};

// The vertex and face lines OFF and ASCII PLY share ("x y z", "3 a b c").
std::string asciiVerticesAndFaces() {
  std::string s;
  for (const char* v : kVertexText) s += std::string(v) + "\n";
  for (const auto& f : kFaces)
    s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
  return s;
}

const MeshCase kMeshCases[] = {
    {"model.obj",
     [] {
       std::string s;
       for (const char* v : kVertexText) s += std::string("v ") + v + "\n";
       for (const auto& f : kFaces)
         s += "f " + std::to_string(f[0] + 1) + " " + std::to_string(f[1] + 1) + " " + std::to_string(f[2] + 1) + "\n";
       return s;
     }},
    {"model.off", [] { return "OFF\n4 5 0\n" + asciiVerticesAndFaces(); }},
    {"ascii.ply", [] { return plyHeader("ascii", "int") + asciiVerticesAndFaces(); }},
    {"binary.ply",
     [] {
       std::string s = plyHeader("binary_little_endian", "uint");
       const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {kNaN, 0, 1}};
       s.append(reinterpret_cast<const char*>(v), sizeof(v));  // x86: little-endian
       for (const auto& f : kFaces) {
         s += char(3);
         for (int i : f) {
           const std::uint32_t u = std::uint32_t(i);
           s.append(reinterpret_cast<const char*>(&u), 4);
         }
       }
       return s;
     }},
};

class SceneBadMesh : public ::testing::TestWithParam<MeshCase> {};

TEST_P(SceneBadMesh, EveryDroppedFaceIsCountedAndReported) {
  test::TempDir dir;
  const std::string path = dir.file(GetParam().name, GetParam().write());
  const Scene s = loadScene(path);
  const SceneMesh* mesh = nullptr;
  for (const SceneMesh& m : s.meshes)
    if (m.name.find(path) != std::string::npos) mesh = &m;
  ASSERT_NE(mesh, nullptr);
  const geo::MeshReport& r = mesh->report;
  EXPECT_EQ(r.inputFaces, 5u);
  EXPECT_EQ(r.triangles, 1u);
  EXPECT_EQ(r.droppedInvalidIndex, 1u);
  EXPECT_EQ(r.droppedDegenerate, 1u);
  EXPECT_EQ(r.droppedNonFinite, 1u);
  EXPECT_EQ(r.droppedDuplicate, 1u);
  EXPECT_EQ(r.inputFaces, r.triangles + r.droppedTotal());
  EXPECT_TRUE(hasWarning(s, path + ": 1 triangle, 4 dropped (1 invalid index, 1 degenerate, "
                                   "1 non-finite, 1 duplicate)"))
      << (s.warnings.empty() ? "no warnings" : s.warnings[0]);
}

INSTANTIATE_TEST_SUITE_P(Formats, SceneBadMesh, ::testing::ValuesIn(kMeshCases),
                         [](const ::testing::TestParamInfo<MeshCase>& info) {
                           std::string n = info.param.name;
                           for (char& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return n;
                         });

TEST(SceneBadInputs, StlNanVertexAndRepeatedCornerAreCounted) {
  // STL has no indices: a facet with a NaN corner or two equal corners is what can go wrong.
  test::TempDir dir;
  const std::string path =
      dir.file("facets.stl",
               "solid x\n"
               "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
               "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex nan 1 0\nendloop\n"
               "endfacet\n"
               "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
               "endsolid x\n");
  const Scene s = loadScene(path);
  EXPECT_TRUE(hasWarning(s, path + ": 1 triangle, 2 dropped (1 degenerate, 1 non-finite)"));
}

TEST(SceneBadInputs, HeadersClaimingABillionElementsAreRejectedBeforeAllocating) {
  test::TempDir dir;
  // OFF and PLY vertex counts are in geometry_io_test (huge_header.*); here the face counts and
  // a binary STL whose facet count is 10^9.
  const std::string off = dir.file("faces.off", "OFF\n3 1000000000 0\n0 0 0\n1 0 0\n0 1 0\n");
  expectError([&] { loadScene(off); }, off, "header claims 3 vertices and 1000000000 faces");
  std::string ply = plyHeader("binary_little_endian", "int");
  ply.replace(ply.find("face 5"), 6, "face 1000000000");
  ply += std::string(12 * 4, '\0');
  const std::string plyPath = dir.file("faces.ply", ply);
  expectError([&] { loadScene(plyPath); }, plyPath, "1000000000 face elements");
  std::string stl(80, ' ');
  const std::uint32_t facets = 1000000000;
  stl.append(reinterpret_cast<const char*>(&facets), 4);
  stl += std::string(50, '\0');  // one facet: not binary by size, and no ascii facet either
  const std::string stlPath = dir.file("facets.stl", stl);
  expectError([&] { loadScene(stlPath); }, stlPath,
              "binary STL header claims 1000000000 triangles (50000000084 bytes), the file has "
              "134 bytes (1 triangle): truncated");
}

// A binary STL whose count disagrees with its size was read as ascii and
// reported "0 triangles, 0 dropped" (no triangles left); the message now gives both counts,
// also for a header beginning with "solid" (as many exporters write) and for extra bytes.
TEST(SceneBadInputs, BinaryStlWhoseCountDisagreesWithItsSizeSaysBoth) {
  test::TempDir dir;
  auto binaryStl = [](const std::string& header, std::uint32_t claimed, int facets, int extra) {
    std::string stl = header + std::string(80 - header.size(), ' ');
    stl.append(reinterpret_cast<const char*>(&claimed), 4);
    const float tri[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    for (int f = 0; f < facets; ++f) {
      stl.append(reinterpret_cast<const char*>(tri), sizeof tri);
      stl += std::string(2, '\0');
    }
    return stl + std::string(std::size_t(extra), '\0');
  };
  const std::string truncated = dir.file("truncated.stl", binaryStl("solid exported", 5, 2, 0));
  expectError([&] { loadScene(truncated); }, truncated,
              "binary STL header claims 5 triangles (334 bytes), the file has 184 bytes (2 "
              "triangles): truncated");
  const std::string longer = dir.file("longer.stl", binaryStl("", 1, 2, 7));
  expectError([&] { loadScene(longer); }, longer,
              "binary STL header claims 1 triangle (134 bytes), the file has 191 bytes (2 "
              "triangles and 7 bytes more)");
  const std::string tiny = dir.file("tiny.stl", "not a mesh");
  expectError([&] { loadScene(tiny); }, tiny, "not an STL file: 10 bytes");
  // The same bytes with a matching count load.
  const Scene ok = loadScene(dir.file("ok.stl", binaryStl("solid exported", 2, 2, 0)));
  EXPECT_EQ(ok.meshes.size(), 2u);  // the mesh and the bare file's floor
}

// Two vertex elements: the second would add positions without the first one's normals (found
// by fuzzing, tests/fuzz/regressions/ply/).
TEST(SceneBadInputs, PlyWithTwoVertexElementsIsRejected) {
  test::TempDir dir;
  const std::string path = dir.file("two.ply",
                                    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                    "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                                    "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                    "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n0 0 1\n3 0 1 3\n");
  expectError([&] { loadScene(path); }, path, "more than one vertex element");
}

// ---------------------------------------------------------------------------------------------
// EXR textures of a scene (hard-cases.md: "truncated, huge data windows, deep or multi-part
// files, NaN/Inf texels: rejected or sanitised with a warning"). The readers' own cases are in
// core_image_io_test; here the scene must pass the warning on and name the texture on failure.

TEST(SceneBadInputs, ExrTextureNonFiniteTexelsAreSanitisedWithASceneWarning) {
  test::TempDir dir;
  Image img(3, 2, 3, 0.25f);
  img.at(0, 0, 0) = kNaN;
  img.at(2, 1, 1) = std::numeric_limits<float>::infinity();
  const std::string exr = dir.file("tex.exr", "");
  writeExr(exr, {{"", &img}});
  const std::string path = dir.file("scene.json", sceneWithTexture("tex.exr"));
  const Scene s = loadScene(path);
  ASSERT_EQ(s.textures.size(), 1u);  // shared by the material and the light
  for (float v : s.textures[0].image.data) EXPECT_TRUE(std::isfinite(v));
  EXPECT_TRUE(hasWarning(s, "tex.exr: replaced 2 non-finite texels with 0"));
}

TEST(SceneBadInputs, BrokenExrTextureIsAnErrorNamingTheTexture) {
  test::TempDir dir;
  Image img(8, 8, 3, 0.5f);
  const std::string good = dir.file("good.exr", "");
  writeExr(good, {{"", &img}});
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  const std::string truncated = dir.file("truncated.exr", bytes.substr(0, bytes.size() / 2));
  expectError([&] { loadScene(dir.file("a.json", sceneWithTexture("truncated.exr"))); }, truncated, "");
  const std::string foreign = dir.file("foreign.exr", "P6\n1 1\n255\nabc");
  expectError([&] { loadScene(dir.file("b.json", sceneWithTexture("foreign.exr"))); }, foreign, "");
}

// A number beyond double's range is not a parse_error in nlohmann's terms (out_of_range 406):
// it must still be one line naming the file (found by fuzzing, tests/fuzz/regressions/json/).
TEST(SceneBadInputs, SceneNumberBeyondDoubleIsInvalidJson) {
  test::TempDir dir;
  const std::string path = dir.file("big.json", R"({"lights": [{"intensity": 1e+315}]})");
  expectError([&] { loadScene(path); }, path, "invalid JSON: number overflow parsing '1e+315'");
}

// ---------------------------------------------------------------------------------------------
// Render parameters that live in the scene (hard-cases.md: "zero light size"): every light
// shape, from a scene file, from --set, and from a glTF EXT_lights_area light.

TEST(SceneBadInputs, ZeroSizedLightsAreRejectedForEveryShape) {
  test::TempDir dir;
  const std::string path = dir.file("lights.json", R"({"objects": [{"shape": "plane"}],
                         "lights": [{"type": "rect", "size": [1, 1]}]})");
  EXPECT_NO_THROW(loadScene(path));
  expectError([&] { loadScene(path, {"lights.0.size=[1,0]"}); }, path,
              "lights[0].size: an area light needs a positive size");
  expectError([&] { loadScene(path, {"lights.0.size=0"}); }, path,
              "lights[0].size: an area light needs a positive size");
  for (const std::string shape : {"disk", "sphere"}) {
    SCOPED_TRACE(shape);
    expectError(
        [&] {
          loadScene(path, {"lights.0.type=" + shape, "lights.0.radius=0"});
        },
        path, "lights[0].radius: an area light needs a positive radius");
  }
  // A glTF area light of size 0, and one whose node scales it to nothing.
  Json doc = cubeDocument();
  doc["extensionsUsed"] = Json::array({"EXT_lights_area"});
  doc["extensions"] = Json::parse(R"({"EXT_lights_area": {"lights": [{"type": "rect",
                                      "size": 0}]}})");
  doc["nodes"].push_back(Json::parse(R"({"extensions": {"EXT_lights_area": {"light": 0}}})"));
  doc["scenes"][0]["nodes"].push_back(1);
  const std::string gltf = dir.file("zero_light.gltf", doc.dump());
  expectError([&] { loadScene(gltf); }, gltf, "size and rect.aspect must be positive");
  doc["extensions"]["EXT_lights_area"]["lights"][0]["size"] = 1;
  doc["nodes"][1]["scale"] = Json::array({1, 0, 1});
  const std::string flat = dir.file("flat_light.gltf", doc.dump());
  const detail::Model m = detail::loadGltf(flat);
  EXPECT_TRUE(m.lights.empty());
  bool warned = false;
  for (const std::string& w : m.warnings) warned = warned || w.find("node 1: singular") != std::string::npos;
  EXPECT_TRUE(warned);
}

// A key given twice in a scene file kept the last value silently. Refused
// with the key, the file and where it is; comments still parse.
TEST(SceneBadInputs, DuplicateKeysAreRefusedWithTheKeyAndWhere) {
  test::TempDir dir;
  const std::string shape =
      dir.file("shape.json", R"({"objects": [{"shape": "box", "shape": "sphere"}], "lights": [{}]})");
  expectError([&] { loadScene(shape); }, shape, "objects[0]: duplicate key 'shape'");
  const std::string nested = dir.file("nested.json", R"({
    "objects": [{"shape": "box"},
                {"shape": "box", "spin": {"axis": [0, 1, 0], /* again: */ "axis": [1, 0, 0]}}],
    "lights": [{}]})");
  expectError([&] { loadScene(nested); }, nested, "objects[1].spin: duplicate key 'axis'");
  const std::string top = dir.file("top.json", R"({"lights": [{}], "objects": [{"shape": "box"}], "lights": []})");
  expectError([&] { loadScene(top); }, top, "scene: duplicate key 'lights'");
  // The same key in sibling objects is not a duplicate.
  const std::string ok =
      dir.file("ok.json", R"({"objects": [{"shape": "box"}, {"shape": "box", "translate": [2, 0, 0]}],
                     "lights": [{"position": [0, 4, 0]}, {"position": [1, 4, 0]}]})");
  EXPECT_EQ(loadScene(ok).meshes.size(), 2u);
}

// A folder given as a mesh said "not found"; a material name with no
// materials defined listed "(known: )".
TEST(SceneBadInputs, MisleadingMessagesSayWhatIsWrong) {
  test::TempDir dir;
  std::filesystem::create_directories(dir.path() + "/folder.obj");
  const std::string scene = dir.file("folder.json", R"({"objects": [{"file": "folder.obj"}], "lights": [{}]})");
  expectError([&] { loadScene(scene); }, scene, "'folder.obj' (");
  expectError([&] { loadScene(scene); }, scene, "folder.obj) is a folder, not a file");
  expectError([&] { loadScene(dir.path() + "/folder.obj"); }, "folder.obj", "is a folder, not a file");
  const std::string red = dir.file("red.json", R"({"objects": [{"shape": "box", "material": "red"}], "lights": [{}]})");
  expectError([&] { loadScene(red); }, red, "unknown material 'red' (the scene's \"materials\" defines none)");
  const std::string known = dir.file("known.json", R"({"materials": [{"name": "blue"}],
      "objects": [{"shape": "box", "material": "red"}], "lights": [{}]})");
  expectError([&] { loadScene(known); }, known, "unknown material 'red' (known: blue)");
}

// An area light float cannot hold. Size 1e19 reached Embree and
// aborted (its rays are valid up to 1.8e18); 1e-30 was refused as needing "a positive size".
// Both bounds come from float (sqrt(FLT_MAX / 12) for squared distances; 4 float spacings at
// the light's position), not from the scene's size.
TEST(SceneBadInputs, LightExtentsFloatCannotHoldAreRefusedSayingSo) {
  const std::string cube = test::sourcePath("scenes/hard/01-cube-on-plane.json");
  expectError([&] { loadScene(cube, {"lights.0.size=1e19"}); }, cube,
              "lights[0] 'key': size [1e+19, 1e+19] is beyond what float can hold");
  expectError([&] { loadScene(cube, {"lights.0.size=1e-30"}); }, cube,
              "size [1e-30, 1e-30] is below what float resolves at the light's position");
  expectError(
      [&] {
        loadScene(cube, {"lights.0.type=disk", "lights.0.radius=1e-30"});
      },
      cube, "radius 1e-30 is below what float resolves");
  // Relative to the position: 1e-5 resolves at |position| 4 (4 spacings = 1.9e-6), not at 1e3
  // (2.4e-4).
  EXPECT_NO_THROW(loadScene(cube, {"lights.0.size=1e-5"}));
  expectError(
      [&] {
        loadScene(cube, {"lights.0.size=1e-5", "lights.0.position=[0,1000,0]"});
      },
      cube, "is below what float resolves at the light's position");
  // Just inside the upper bound: loads (rendered by scenes/hard/31-huge-light.json).
  EXPECT_NO_THROW(loadScene(cube, {"lights.0.size=7e18"}));
  // The reach counts from the origin: a smaller light far out is refused too.
  expectError(
      [&] {
        loadScene(cube, {"lights.0.size=1e18", "lights.0.position=[0,5e18,0]"});
      },
      cube, "the light reaches 5.71e+18 from the origin");
}

// OBJ mtllib/usemtl were ignored (a red Kd rendered grey). Faces after
// `usemtl NAME` now get that material's Kd, map_Kd and d / Tr, one mesh per material.
const Material& materialOf(const Scene& s, const std::string& meshSuffix) {
  for (const SceneMesh& m : s.meshes)
    if (m.name.size() >= meshSuffix.size() &&
        m.name.compare(m.name.size() - meshSuffix.size(), meshSuffix.size(), meshSuffix) == 0)
      return s.materials.at(std::size_t(m.material));
  ADD_FAILURE() << "no mesh named *" << meshSuffix;
  return s.materials.at(0);
}

const SceneMesh* meshNamed(const Scene& s, const std::string& suffix) {
  for (const SceneMesh& m : s.meshes)
    if (m.name.size() >= suffix.size() && m.name.compare(m.name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return &m;
  return nullptr;
}

TEST(SceneBadInputs, ObjMaterialsGiveEachFaceItsKdOpacityAndTexture) {
  test::TempDir dir;
  Image png(2, 2, 4, 1.0f);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) png.at(x, y, 1) = png.at(x, y, 2) = 0.0f;  // red, opaque
  dir.file("tex/.keep", "");                                               // the texture's folder
  writePng(dir.path() + "/tex/red.png", png);
  dir.file("m.mtl",
           "newmtl red\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 10\n"
           "newmtl half\nKd 0.2 0.4 0.6\nd 0.5\nKs 1 1 1\n"
           "newmtl tr\nTr 0.25\n"
           "newmtl textured\nmap_Kd tex/red.png\nmap_Bump tex/red.png\n");
  // Two red triangles apart (the second after another material), one for each other material,
  // and one degenerate face of `half` dropped and counted in that mesh only.
  const std::string obj = dir.file("m.obj",
                                   "mtllib m.mtl\n"
                                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 3 0 0\nv 2 1 0\nv 4 0 0\nv 5 0 0\nv 4 1 0\n"
                                   "v 6 0 0\nv 7 0 0\nv 6 1 0\nv 8 0 0\nv 9 0 0\nv 8 1 0\nvt 0 0\n"
                                   "usemtl red\nf 1 2 3\nusemtl half\nf 4 5 6\nf 4 4 5\nusemtl red\nf 13 14 15\n"
                                   "usemtl tr\nf 7 8 9\nusemtl textured\nf 10/1 11/1 12/1\nusemtl nosuch\nf 1 3 2\n");
  const Scene s = loadScene(obj);
  const SceneMesh* red = meshNamed(s, "m.obj#red");
  ASSERT_NE(red, nullptr);
  EXPECT_EQ(red->mesh.triangles.size(), 2u);
  EXPECT_EQ(red->report.droppedTotal(), 0u);
  const Material& r = materialOf(s, "m.obj#red");
  EXPECT_NEAR(r.baseColor.r, 1.0f, 1e-6f);
  EXPECT_NEAR(r.baseColor.g, 0.0f, 1e-6f);
  EXPECT_NEAR(r.opacity, 1.0f, 1e-6f);
  EXPECT_EQ(r.alphaMode, AlphaMode::Opaque);
  const Material& half = materialOf(s, "m.obj#half");
  EXPECT_NEAR(half.opacity, 0.5f, 1e-6f);
  EXPECT_EQ(half.alphaMode, AlphaMode::Blend);
  EXPECT_NEAR(half.baseColor.b, 0.6f, 1e-6f);
  const SceneMesh* halfMesh = meshNamed(s, "m.obj#half");
  ASSERT_NE(halfMesh, nullptr);
  EXPECT_EQ(halfMesh->mesh.triangles.size(), 1u);
  EXPECT_EQ(halfMesh->report.droppedDegenerate, 1u);
  EXPECT_TRUE(hasWarning(s, obj + "#half: 1 triangle, 1 dropped (1 degenerate)"));
  EXPECT_NEAR(materialOf(s, "m.obj#tr").opacity, 0.75f, 1e-6f);
  EXPECT_NEAR(materialOf(s, "m.obj#tr").baseColor.r, 0.8f, 1e-6f);  // no Kd: the default
  const Material& tex = materialOf(s, "m.obj#textured");
  ASSERT_GE(tex.baseColorTexture, 0);
  const Image& img = s.textures.at(std::size_t(tex.baseColorTexture)).image;
  ASSERT_EQ(img.width, 2);
  EXPECT_NEAR(img.at(1, 1, 0), 1.0f, 1e-3f);
  EXPECT_NEAR(img.at(1, 1, 1), 0.0f, 1e-3f);
  ASSERT_FALSE(meshNamed(s, "m.obj#textured")->mesh.uvs.empty());
  // The unknown name keeps its faces, with the default material, and says so.
  EXPECT_EQ(meshNamed(s, "m.obj#nosuch")->material, 0);
  EXPECT_TRUE(hasWarning(s, obj + ": usemtl 'nosuch': no such material in "));
  // Ks/Ns map onto the metallic-roughness BRDF: a dielectric lobe, roughness (2 / (Ns + 2))^(1/4).
  EXPECT_TRUE(hasWarning(s,
                         "m.mtl: Ks is read as a dielectric specular lobe (F0 0.04, roughness from Ns); "
                         "its strength and colour are not used, in 2 materials (red, half)"));
  EXPECT_FALSE(hasWarning(s, "'Ks' not used"));
  EXPECT_FALSE(hasWarning(s, "'Ns' not used"));
  const Material& redMaterial = materialOf(s, "m.obj#red");
  EXPECT_EQ(redMaterial.brdf, BrdfModel::MetallicRoughness);
  EXPECT_NEAR(redMaterial.roughness, std::pow(2.0f / 12.0f, 0.25f), 1e-6f);
  EXPECT_EQ(redMaterial.metallic, 0.0f);
  EXPECT_EQ(materialOf(s, "m.obj#half").roughness, 1.0f);         // no Ns
  EXPECT_EQ(materialOf(s, "m.obj#tr").brdf, BrdfModel::Lambert);  // no Ks
  EXPECT_TRUE(hasWarning(s, "m.mtl: 'map_Bump' not used"));
  EXPECT_FALSE(hasWarning(s, "'Kd' not used"));
  EXPECT_FALSE(hasWarning(s, "'d' not used"));
  std::size_t triangles = 0;
  for (const SceneMesh& m : s.meshes) triangles += m.mesh.triangles.size();
  EXPECT_EQ(triangles, 6u + 2u);  // the OBJ's six kept faces and the bare-file floor
}

TEST(SceneBadInputs, ObjMaterialProblemsAreWarnedAndTheObjectMaterialWins) {
  test::TempDir dir;
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string missing = dir.file("missing.obj", "mtllib gone.mtl\nusemtl a\n" + tri);
  const Scene b = loadScene(missing);
  EXPECT_TRUE(hasWarning(b, missing + ": mtllib 'gone.mtl': no such file"));
  EXPECT_TRUE(hasWarning(b, missing + ": usemtl 'a': no material library was read"));
  const std::string outside = dir.file("sub/out.obj", "mtllib ../m.mtl\nusemtl a\n" + tri);
  dir.file("m.mtl", "newmtl a\nKd 1 0 0\n");
  EXPECT_TRUE(hasWarning(loadScene(outside), "mtllib '../m.mtl': leaves its folder ('..')"));
  dir.file("t.mtl", "newmtl a\nKd 1 0 0\nmap_Kd /etc/passwd.png\nd 2\n");
  const std::string obj = dir.file("t.obj", "mtllib t.mtl\nusemtl a\n" + tri);
  const Scene t = loadScene(obj);
  EXPECT_TRUE(hasWarning(t, "material 'a': map_Kd '/etc/passwd.png' is an absolute path"));
  EXPECT_TRUE(hasWarning(t, "material 'a': d '2' is not a number in [0, 1]; ignored"));
  EXPECT_NEAR(materialOf(t, "t.obj#a").opacity, 1.0f, 1e-6f);
  EXPECT_EQ(materialOf(t, "t.obj#a").baseColorTexture, -1);
  // A scene file's "material" replaces the OBJ's; its "opacity" overrides the OBJ's opacity.
  const std::string scene = dir.file("s.json", R"({"materials": [{"name": "blue", "baseColor": [0, 0, 1]}],
                    "objects": [{"file": "t.obj", "material": "blue"},
                                {"file": "t.obj", "opacity": 0.3}],
                    "lights": [{"position": [0, 4, 0]}]})");
  const Scene j = loadScene(scene);
  ASSERT_EQ(j.meshes.size(), 2u);
  EXPECT_NEAR(j.materials.at(std::size_t(j.meshes[0].material)).baseColor.b, 1.0f, 1e-6f);
  const Material& faded = j.materials.at(std::size_t(j.meshes[1].material));
  EXPECT_NEAR(faded.baseColor.r, 1.0f, 1e-6f);
  EXPECT_NEAR(faded.opacity, 0.3f, 1e-6f);
  const Scene c = loadScene(dir.file("plain.obj", tri));
  EXPECT_FALSE(hasWarning(c, "mtl"));
}

}  // namespace
}  // namespace penumbra
