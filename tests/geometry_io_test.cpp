// loadMeshFile on small hand-written files, generated binary files, bad inputs and the real
// models of Debian's assimp-testmodels; OpenMesh serves as an oracle where the file is valid.
#include <gtest/gtest.h>

#include "test_util.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "geometry/mesh.h"

namespace penumbra::geo {
namespace {

namespace fs = std::filesystem;

std::string dataPath(const std::string& name) {
  return std::string(PENUMBRA_SOURCE_DIR) + "/tests/data/geometry/" + name;
}

const std::string kAssimp = "/usr/share/assimp/models/";

// A file of its own per test, as CTest may run tests of this binary in parallel.
std::string tempPath(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() / "penumbra_geometry_test";
  fs::create_directories(dir);
  return (dir / (std::string(info->name()) + "_" + name)).string();
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

template <typename T>
void append(std::string& out, T value, bool bigEndian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (bigEndian) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

// Expects loadMeshFile to throw penumbra::Error naming the file and containing `problem`.
void expectLoadError(const std::string& path, const std::string& problem) {
  MeshReport r;
  test::expectError([&] { loadMeshFile(path, r); }, path, problem);
}

void expectClosedCube(const TriangleMesh& m, const MeshReport& r) {
  EXPECT_EQ(r.triangles, 12u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(r.inputFaces, 6u);
  EXPECT_EQ(r.polygonsTriangulated, 6u);
  EXPECT_EQ(r.droppedTotal(), 0u);
  EXPECT_TRUE(r.closed) << r.summary();
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(buildEdgeTopology(m).edges.size(), 18u);
}

TEST(GeometryIo, ObjQuadsNegativeIndicesAndAttributes) {
  MeshReport r;
  const TriangleMesh m = loadMeshFile(dataPath("cube_quads.obj"), r);
  expectClosedCube(m, r);
  EXPECT_EQ(r.inputVertices, 8u);
  // One vertex per (v, vt, vn) corner: 6 faces x 4 corners.
  EXPECT_EQ(m.positions.size(), 24u);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  // Every corner's normal is its face normal, which the winding agrees with.
  for (const glm::uvec3& t : m.triangles) {
    const glm::vec3 n = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    EXPECT_GT(glm::dot(n, m.normals[t.x]), 0.0f);
  }
  EXPECT_EQ(m.uvs[m.triangles[0].x], glm::vec2(0, 0));
}

TEST(GeometryIo, OffPlyStl) {
  MeshReport r;
  TriangleMesh m = loadMeshFile(dataPath("cube.off"), r);
  expectClosedCube(m, r);
  EXPECT_TRUE(m.normals.empty());

  m = loadMeshFile(dataPath("cube_normals.ply"), r);
  expectClosedCube(m, r);
  ASSERT_EQ(m.normals.size(), 8u);
  EXPECT_FLOAT_EQ(m.normals[6].x, 0.577f);
  EXPECT_TRUE(m.uvs.empty());

  m = loadMeshFile(dataPath("tetra.stl"), r);
  EXPECT_EQ(r.triangles, 4u);
  EXPECT_EQ(r.inputFaces, 4u);
  EXPECT_TRUE(r.closed) << r.summary();
  EXPECT_EQ(buildEdgeTopology(m).weldedPositions.size(), 4u);
}

TEST(GeometryIo, FlippedTriangleAndNonManifoldBook) {
  MeshReport r;
  loadMeshFile(dataPath("cube_flipped.off"), r);
  EXPECT_EQ(r.triangles, 12u);
  EXPECT_EQ(r.inconsistentEdges, 3u);
  EXPECT_FALSE(r.closed);
  // The flipped first face is added first: its three neighbours are refused and copied.
  EXPECT_EQ(r.duplicatedVertices, 9u);

  // Hard case 6: nothing is dropped, the spine is reported; the silhouette mesh copies the
  // vertices of the one triangle add_face refuses on the spine (silhouette.h).
  const TriangleMesh book = loadMeshFile(dataPath("book.obj"), r);
  EXPECT_EQ(r.triangles, 6u);
  EXPECT_EQ(r.polygonsTriangulated, 3u);
  EXPECT_EQ(r.nonManifoldEdges, 1u);
  EXPECT_EQ(r.openEdges, 9u);
  EXPECT_EQ(r.duplicatedVertices, 3u);
  EXPECT_EQ(r.droppedTotal(), 0u);
}

TEST(GeometryIo, MalformedObjLoadsWithCounts) {
  MeshReport r;
  const TriangleMesh m = loadMeshFile(dataPath("malformed.obj"), r);
  EXPECT_EQ(r.inputVertices, 6u);
  EXPECT_EQ(r.inputFaces, 12u);
  EXPECT_EQ(r.droppedInvalidIndex, 4u);  // 99, 0, -9 (before the first vertex), "abc"
  EXPECT_EQ(r.droppedNonFinite, 1u);     // uses the nan vertex
  EXPECT_EQ(r.droppedDegenerate, 2u);    // "1 1 2" and a two-vertex face
  EXPECT_EQ(r.droppedDuplicate, 2u);     // rotated and reversed copies
  EXPECT_EQ(r.hugeCoordinates, 1u);
  EXPECT_EQ(r.triangles, 3u);
  EXPECT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(r.inputFaces, r.triangles + r.droppedTotal());
}

// Line and point elements and vertex colours carry nothing penumbra shades: counted and said
// (a line-only OBJ said "0 dropped"), never silently gone.
TEST(GeometryIo, LinesPointsAndVertexColoursAreCounted) {
  const std::string obj = tempPath("lines.obj");
  writeBytes(obj, "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\nl 1 2\nl 2 3\np 3\n");
  MeshReport r;
  loadMeshFile(obj, r);
  EXPECT_EQ(r.ignoredElements, 3u);
  EXPECT_TRUE(r.vertexColours);
  EXPECT_TRUE(r.worthWarning());
  EXPECT_NE(r.summary().find("3 line/point elements ignored, vertex colours not used"), std::string::npos)
      << r.summary();
  writeBytes(obj, "v 0 0 0\nv 1 0 0\nl 1 2\n");
  expectLoadError(obj, "no triangles left (0 triangles, 0 dropped, 1 line/point elements ignored");
  const std::string ply = tempPath("edges.ply");
  writeBytes(ply,
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\n"
             "property list uchar int vertex_indices\nelement edge 2\nproperty int vertex1\nproperty int vertex2\n"
             "end_header\n0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n0 1\n1 2\n");
  MeshReport p;
  loadMeshFile(ply, p);
  EXPECT_EQ(p.ignoredElements, 2u);
  EXPECT_TRUE(p.vertexColours);
  EXPECT_EQ(p.triangles, 1u);
}

TEST(GeometryIo, NanInAsciiPlyDropsOnlyItsFace) {
  MeshReport r;
  const TriangleMesh m = loadMeshFile(dataPath("nan_vertex.ply"), r);
  EXPECT_EQ(r.droppedNonFinite, 1u);
  EXPECT_EQ(r.triangles, 1u);
  EXPECT_EQ(m.positions[3], glm::vec3(0, 1, 0));  // values after the nan are still read
}

TEST(GeometryIo, BadFilesThrowNamingTheFile) {
  expectLoadError(dataPath("does_not_exist.obj"), "no such file");
  expectLoadError(dataPath("cube.xyz"), "unsupported mesh format");
  expectLoadError(dataPath("huge_header.off"), "1000000000 vertices");
  expectLoadError(dataPath("huge_header.ply"), "1000000000 vertex");
  expectLoadError(dataPath("truncated.off"), "truncated");
  expectLoadError(dataPath("truncated.ply"), "truncated");
  const std::string folder = tempPath("folder.obj");
  fs::create_directories(folder);
  expectLoadError(folder, "is a folder, not a file");
  const std::string empty = tempPath("empty.stl");
  writeBytes(empty, "");
  expectLoadError(empty, "empty file");
  const std::string noFaces = tempPath("points.obj");
  writeBytes(noFaces, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 5\n");
  expectLoadError(noFaces, "no triangles left (0 triangles, 1 dropped (1 invalid index)");
  const std::string hugeList = tempPath("hugelist.ply");
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list int int vertex_indices\nend_header\n";
  for (int i = 0; i < 9; ++i) append(ply, float(i % 4 == 0));
  append(ply, std::int32_t{2000000000});
  writeBytes(hugeList, ply);
  expectLoadError(hugeList, "bad list length");
}

TEST(GeometryIo, GeneratedBinaryPlyBothEndiansAndUppercaseExtension) {
  for (bool big : {false, true}) {
    std::string ply = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                      "property double z\nproperty uchar red\nelement face 2\n"
                      "property list uchar ushort vertex_indices\nproperty int flags\n"
                      "end_header\n";
    const double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (const auto& p : v) {
      for (double c : p) append(ply, c, big);
      append(ply, std::uint8_t{200});
    }
    for (std::uint16_t f : {0, 1}) {
      append(ply, std::uint8_t{3});
      for (std::uint16_t i : {std::uint16_t(0), std::uint16_t(f + 1), std::uint16_t(f + 2)})
        append(ply, std::uint16_t(i % 4), big);
      append(ply, std::int32_t{7}, big);
    }
    const std::string path = tempPath(big ? "big.PLY" : "little.ply");
    writeBytes(path, ply);
    MeshReport r;
    const TriangleMesh m = loadMeshFile(path, r);
    EXPECT_EQ(r.triangles, 2u) << r.summary();
    EXPECT_EQ(r.openEdges, 4u);
    EXPECT_EQ(m.positions[2], glm::vec3(1, 1, 0));
  }
}

TEST(GeometryIo, GeneratedBinaryStlWithNanFacet) {
  std::string stl(80, ' ');
  append(stl, std::uint32_t{3});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float facets[3][9] = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, 0, 1, 0}, {1, 0, 0, nan, 1, 0, 0, 1, 0}};
  for (const auto& f : facets) {
    for (int i = 0; i < 3; ++i) append(stl, 0.0f);  // facet normal, ignored
    for (float c : f) append(stl, c);
    append(stl, std::uint16_t{0});
  }
  const std::string path = tempPath("nan.stl");
  writeBytes(path, stl);
  MeshReport r;
  loadMeshFile(path, r);
  EXPECT_EQ(r.inputFaces, 3u);
  EXPECT_EQ(r.triangles, 2u);
  EXPECT_EQ(r.droppedNonFinite, 1u);
  EXPECT_EQ(r.openEdges, 4u);
}

// Real files from Debian's assimp-testmodels: face counts as their headers or face lists say.
TEST(GeometryIo, AssimpModels) {
  struct Case {
    std::string file;
    std::size_t faces;
  };
  const Case cases[] = {{"PLY/Wuson.ply", 3732},        {"PLY/cube_binary.ply", 12},     {"PLY/cube.ply", 6},
                        {"OFF/Wuson.off", 3732},        {"OBJ/WusonOBJ.obj", 3732},      {"OBJ/spider.obj", 1368},
                        {"STL/Spider_ascii.stl", 1368}, {"STL/Spider_binary.stl", 1368}, {"STL/Wuson.stl", 3732},
                        {"STL/3DSMaxExport.STL", 2000}};
  int loaded = 0;
  for (const Case& c : cases) {
    const std::string path = kAssimp + c.file;
    if (!fs::exists(path)) continue;
    MeshReport r;
    const TriangleMesh m = loadMeshFile(path, r);
    ++loaded;
    EXPECT_EQ(r.inputFaces, c.faces) << c.file;
    if (r.polygonsTriangulated == 0) {
      EXPECT_EQ(r.inputFaces, r.triangles + r.droppedTotal()) << c.file;
    }
    EXPECT_GT(r.triangles, r.inputFaces / 2) << c.file << ": " << r.summary();
    EXPECT_LE(r.triangles, 2 * r.inputFaces) << c.file;
    EXPECT_TRUE(m.normals.empty() || m.normals.size() == m.positions.size()) << c.file;
    EXPECT_TRUE(m.uvs.empty() || m.uvs.size() == m.positions.size()) << c.file;
    std::printf("%-24s %s\n", c.file.c_str(), r.summary().c_str());
  }
  if (loaded == 0) FAIL() << "assimp-testmodels not installed (./setup.sh --deps installs it)";
  // invalid.off announces 4 faces and ends after 3 malformed ones.
  if (fs::exists(kAssimp + "OFF/invalid.off")) expectLoadError(kAssimp + "OFF/invalid.off", "");
}

// Every prefix and many random corruptions of every test file either load or throw
// penumbra::Error; run under the sanitizer build this is the crash check for bad input.
TEST(GeometryIo, TruncatedAndCorruptedFilesNeverCrash) {
  std::vector<std::string> sources;
  for (const auto& entry : fs::directory_iterator(dataPath(""))) {
    sources.push_back(entry.path().string());
  }
  std::sort(sources.begin(), sources.end());
  std::mt19937 rng(99);
  const char kBytes[] = "0123456789 -+.e/\n\r#nafvx\xff";
  std::size_t loads = 0;
  for (const std::string& source : sources) {
    std::ifstream in(source, std::ios::binary);
    const std::string original((std::istreambuf_iterator<char>(in)), {});
    const std::string path = tempPath("fuzz" + fs::path(source).extension().string());
    auto tryLoad = [&](const std::string& bytes) {
      writeBytes(path, bytes);
      MeshReport r;
      try {
        const TriangleMesh m = loadMeshFile(path, r);
        for (const glm::uvec3& t : m.triangles) {
          ASSERT_LT(std::max({t.x, t.y, t.z}), m.positions.size());
        }
        ++loads;
      } catch (const Error& e) {
        EXPECT_EQ(e.where(), path);
      }
    };
    // 40 cuts and 40 corruptions per file keep the file writes (the cost here) near a second.
    for (std::size_t i = 0; i < 40; ++i) tryLoad(original.substr(0, original.size() * i / 40));
    for (int i = 0; i < 40; ++i) {
      std::string bytes = original;
      for (int k = 0; k < 3 && !bytes.empty(); ++k) bytes[rng() % bytes.size()] = kBytes[rng() % (sizeof(kBytes) - 1)];
      tryLoad(bytes);
    }
  }
  EXPECT_GT(loads, 0u);
}

// OpenMesh reads valid PLY and OFF files in file order; positions must match bit for bit.
TEST(GeometryIo, PositionsMatchOpenMesh) {
  omerr().disable();  // OpenMesh complains about Blender's multi-word header comments
  omlog().disable();
  for (const std::string file : {"PLY/Wuson.ply", "PLY/cube_binary.ply", "OFF/Wuson.off"}) {
    const std::string path = kAssimp + file;
    if (!fs::exists(path)) FAIL() << "assimp-testmodels not installed (./setup.sh --deps installs it)";
    OpenMesh::TriMesh_ArrayKernelT<> om;
    ASSERT_TRUE(OpenMesh::IO::read_mesh(om, path));
    MeshReport r;
    const TriangleMesh m = loadMeshFile(path, r);
    ASSERT_LE(m.positions.size(), om.n_vertices()) << file;  // OpenMesh may only add copies
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      const auto p = om.point(OpenMesh::VertexHandle(int(i)));
      ASSERT_EQ(m.positions[i], glm::vec3(p[0], p[1], p[2])) << file << " vertex " << i;
    }
    EXPECT_EQ(r.triangles, om.n_faces()) << file;
  }
}

}  // namespace
}  // namespace penumbra::geo
