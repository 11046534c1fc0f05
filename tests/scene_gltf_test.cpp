// glTF loading: valid layouts, each class of malformed input, and every file Debian's
// assimp-testmodels ships under glTF2/.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "scene/loaders.h"
#include "scene_test_util.h"

namespace penumbra {
namespace {

using test::expectError;
using test::sceneData;

const char* const kAssimpGltf = "/usr/share/assimp/models/glTF2";

detail::Model load(const std::string& name) { return detail::loadGltf(sceneData(name)); }

std::size_t triangles(const detail::Model& m) {
  std::size_t n = 0;
  for (const SceneMesh& s : m.meshes) n += s.mesh.triangles.size();
  return n;
}

bool warned(const detail::Model& m, const std::string& fragment) {
  for (const std::string& w : m.warnings) {
    if (w.find(fragment) != std::string::npos) return true;
  }
  return false;
}

TEST(SceneGltf, CubeInAllContainers) {
  for (const char* name : {"cube.gltf", "cube_external.gltf", "cube.glb", "cube_nul_padded.glb"}) {
    SCOPED_TRACE(name);
    const detail::Model m = load(name);
    ASSERT_EQ(m.meshes.size(), 1u);
    EXPECT_EQ(m.meshes[0].mesh.triangles.size(), 12u);
    EXPECT_NEAR(test::signedVolume(m.meshes[0].mesh), 1.0, 1e-6);
    EXPECT_TRUE(m.meshes[0].report.closed);
  }
}

TEST(SceneGltf, MirroredInstanceKeepsOutwardWinding) {
  const detail::Model m = load("mirrored.gltf");
  ASSERT_EQ(m.meshes.size(), 2u);
  for (const SceneMesh& s : m.meshes) {
    EXPECT_NEAR(test::signedVolume(s.mesh), 1.0, 1e-6) << s.name;
    // Every face normal points away from the instance's centre.
    glm::vec3 centre(0.0f);
    for (const glm::vec3& p : s.mesh.positions) centre += p / float(s.mesh.positions.size());
    for (const glm::uvec3& t : s.mesh.triangles) {
      const glm::vec3 a = s.mesh.positions[t.x], b = s.mesh.positions[t.y], c = s.mesh.positions[t.z];
      EXPECT_GT(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - centre), 0.0f) << s.name;
    }
  }
}

TEST(SceneGltf, HierarchyIsFlattened) {
  const detail::Model m = load("hierarchy.gltf");
  ASSERT_EQ(m.meshes.size(), 1u);
  Scene s;
  s.meshes = m.meshes;
  glm::vec3 lo, hi;
  s.bounds(lo, hi);
  // Scale 2, rotation about Z, then +3 in Y: a 2-unit cube centred at (0, 3, 0).
  EXPECT_NEAR(lo.y, 2.0f, 1e-5f);
  EXPECT_NEAR(hi.y, 4.0f, 1e-5f);
  EXPECT_NEAR(hi.x, 1.0f, 1e-5f);
  EXPECT_NEAR(test::signedVolume(m.meshes[0].mesh), 8.0, 1e-4);
}

TEST(SceneGltf, DeepChainDoesNotOverflowTheStack) {
  test::TempDir dir;
  constexpr int kDepth = 200000;
  std::ostringstream nodes;
  for (int i = 0; i < kDepth; ++i) {
    nodes << (i ? "," : "") << "{\"translation\":[0,0.0001,0]";
    if (i + 1 < kDepth)
      nodes << ",\"children\":[" << i + 1 << "]";
    else
      nodes << ",\"mesh\":0";
    nodes << "}";
  }
  std::ifstream in(sceneData("cube.gltf"));
  std::stringstream cube;
  cube << in.rdbuf();
  std::string text = cube.str();
  auto doc = detail::Json::parse(text);
  doc["nodes"] = detail::Json::parse("[" + nodes.str() + "]");
  const std::string path = dir.file("deep.gltf", doc.dump());
  const detail::Model m = detail::loadGltf(path);
  ASSERT_EQ(m.meshes.size(), 1u);
  Scene s;
  s.meshes = m.meshes;
  glm::vec3 lo, hi;
  s.bounds(lo, hi);
  EXPECT_NEAR(lo.y, kDepth * 0.0001f - 0.5f, 1e-2f);
}

TEST(SceneGltf, SingularNodeDroppedWithWarning) {
  const detail::Model m = load("singular_node.gltf");
  EXPECT_EQ(m.meshes.size(), 1u);  // node 1 and its child 2 are dropped
  EXPECT_TRUE(warned(m, "singular"));
}

TEST(SceneGltf, StridedExactFitIsAccepted) {
  const detail::Model m = load("strided_exact.gltf");
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_EQ(m.meshes[0].mesh.triangles.size(), 1u);
  EXPECT_EQ(m.meshes[0].mesh.positions[2], glm::vec3(0, 1, 0));
}

TEST(SceneGltf, StridedOneByteShortIsRejected) {
  expectError([] { load("strided_short.gltf"); }, sceneData("strided_short.gltf"), "accessor 0");
}

TEST(SceneGltf, PrimitiveModes) {
  const detail::Model m = load("modes.gltf");
  EXPECT_EQ(triangles(m), 4u);  // strip 2 + fan 2
  EXPECT_TRUE(warned(m, "POINTS primitive ignored"));
  EXPECT_TRUE(warned(m, "LINES primitive ignored"));
  EXPECT_TRUE(warned(m, "no POSITION"));
  for (const SceneMesh& s : m.meshes) {
    for (const glm::uvec3& t : s.mesh.triangles) {
      const glm::vec3 a = s.mesh.positions[t.x], b = s.mesh.positions[t.y], c = s.mesh.positions[t.z];
      EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "strip/fan winding must stay +Z";
    }
  }
  expectError([] { load("mode_unknown.gltf"); }, sceneData("mode_unknown.gltf"), "unknown primitive mode 9");
}

TEST(SceneGltf, Materials) {
  const detail::Model m = load("materials.gltf");
  ASSERT_EQ(m.materials.size(), 4u);
  EXPECT_EQ(m.materials[0].alphaMode, AlphaMode::Opaque);
  EXPECT_EQ(m.materials[0].opacity, 1.0f);  // alpha ignored when OPAQUE
  EXPECT_EQ(m.materials[0].baseColor, glm::vec3(1, 0, 0));
  EXPECT_EQ(m.materials[1].alphaMode, AlphaMode::Mask);
  EXPECT_EQ(m.materials[1].opacity, 0.0f);  // 0.3 < cutoff 0.5
  EXPECT_EQ(m.materials[2].alphaMode, AlphaMode::Blend);
  EXPECT_NEAR(m.materials[2].opacity, 0.4f, 1e-6f);
  ASSERT_EQ(m.materials[3].baseColorTexture, 0);
  ASSERT_EQ(m.textures.size(), 2u);
  const Image& img = m.textures[0].image;
  ASSERT_EQ(img.width, 2);
  ASSERT_EQ(img.channels, 4);
  EXPECT_FLOAT_EQ(img.at(0, 0, 0), 1.0f);  // red
  EXPECT_FLOAT_EQ(img.at(0, 0, 1), 0.0f);
  EXPECT_FLOAT_EQ(img.at(1, 0, 1), 1.0f);                // green
  EXPECT_FLOAT_EQ(img.at(0, 1, 2), 1.0f);                // blue
  EXPECT_NEAR(img.at(1, 1, 3), 128.0f / 255.0f, 1e-6f);  // alpha stays linear
  ASSERT_EQ(m.meshes.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(m.meshes[std::size_t(i)].material, i);
  // The specification's BRDF, its factors (default 1) and the metallic-roughness texture, which
  // is linear data: the same image decoded a second time, without the sRGB curve.
  for (const Material& mat : m.materials) EXPECT_EQ(mat.brdf, BrdfModel::MetallicRoughness);
  EXPECT_EQ(m.materials[0].metallic, 0.25f);
  EXPECT_EQ(m.materials[0].roughness, 0.5f);
  EXPECT_EQ(m.materials[1].metallic, 1.0f);
  EXPECT_EQ(m.materials[1].roughness, 1.0f);
  EXPECT_EQ(m.materials[3].metallicRoughnessTexture, 1);
}

TEST(SceneGltf, MaskWithATextureIsAlphaTested) {
  const detail::Model m = load("mask_textured.gltf");
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].alphaMode, AlphaMode::Mask);
  EXPECT_EQ(m.materials[0].opacity, 1.0f);  // the constant alpha 0.9 passes the cutoff 0.6
  EXPECT_NEAR(m.materials[0].alphaFactor, 0.9f, 1e-6f);
  EXPECT_NEAR(m.materials[0].alphaCutoff, 0.6f, 1e-6f);
  EXPECT_FALSE(warned(m, "texture alpha"));
  // One texel's alpha 128/255 x 0.9 is below the cutoff: the surface has holes.
  const Scene s = loadScene(sceneData("mask_textured.gltf"));
  bool tested = false;
  for (const SceneMesh& mesh : s.meshes) tested = tested || s.alphaTested(mesh.material);
  EXPECT_TRUE(tested);
}

TEST(SceneGltf, Lights) {
  const detail::Model m = load("lights.gltf");
  ASSERT_EQ(m.lights.size(), 4u);  // point, spot-as-point, rect, disk; directional dropped
  EXPECT_EQ(m.lights[0].shape, LightShape::Point);
  EXPECT_EQ(m.lights[0].position, glm::vec3(0, 5, 0));
  EXPECT_EQ(m.lights[0].intensity, 10.0f);
  EXPECT_EQ(m.lights[0].color, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_EQ(m.lights[1].shape, LightShape::Point);
  EXPECT_TRUE(warned(m, "spot light treated as a point light"));
  EXPECT_TRUE(warned(m, "directional"));
  const Light& rect = m.lights[2];
  EXPECT_EQ(rect.shape, LightShape::Rect);
  EXPECT_NEAR(rect.size.x, 3.0f, 1e-5f);  // size * aspect
  EXPECT_NEAR(rect.size.y, 2.0f, 1e-5f);
  EXPECT_NEAR(rect.normal.y, -1.0f, 1e-5f);  // local -Z turned down by the node
  EXPECT_NEAR(rect.position.y, 4.0f, 1e-5f);
  EXPECT_EQ(rect.intensity, 5.0f);
  const Light& disk = m.lights[3];
  EXPECT_EQ(disk.shape, LightShape::Disk);
  EXPECT_NEAR(disk.size.x, 0.5f, 1e-6f);  // radius = size / 2
  EXPECT_NEAR(disk.normal.z, -1.0f, 1e-6f);
}

TEST(SceneGltf, IndexOutOfRangeDropsAndCounts) {
  const detail::Model m = load("index_out_of_range.gltf");
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_EQ(m.meshes[0].mesh.triangles.size(), 10u);
  EXPECT_EQ(m.meshes[0].report.droppedInvalidIndex, 2u);
  EXPECT_TRUE(warned(m, "indices >= vertex count"));
}

struct BadCase {
  const char* file;
  const char* fragment;
};

class SceneGltfBad : public ::testing::TestWithParam<BadCase> {};

TEST_P(SceneGltfBad, RejectedWithOneLineNamingTheFile) {
  const std::string path = sceneData(GetParam().file);
  expectError([&] { loadScene(path); }, path, GetParam().fragment);
}

INSTANTIATE_TEST_SUITE_P(
    Inputs, SceneGltfBad,
    ::testing::Values(
        BadCase{"accessor_overrun.gltf", "accessor 0"}, BadCase{"bufferview_overrun.gltf", "bufferView 1"},
        BadCase{"accessor_count0.gltf", "count is 0"},
        BadCase{"accessor_misaligned.gltf", "not a multiple of the component size"},
        BadCase{"accessor_wrong_type.gltf", "unsupported type/componentType"},
        BadCase{"index_not_multiple_of_3.gltf", "not a multiple of 3"}, BadCase{"uri_parent.gltf", "leaves its folder"},
        BadCase{"uri_percent_parent.gltf", "leaves its folder"}, BadCase{"uri_absolute.gltf", "absolute path"},
        BadCase{"uri_file.gltf", "scheme 'file:'"}, BadCase{"uri_http.gltf", "scheme 'http:'"},
        BadCase{"uri_shell.gltf", "shell metacharacter ';'"}, BadCase{"uri_missing.gltf", "not found"},
        BadCase{"data_uri_bad_base64.gltf", "not valid base64"},
        BadCase{"buffer_declared_huge.gltf", "declares 900000000 bytes"},
        BadCase{"basisu_required.gltf", "KHR_texture_basisu"}, BadCase{"node_cycle.gltf", "cycle"},
        BadCase{"node_two_parents.gltf", "two parents"}, BadCase{"node_self_child.gltf", "its own child"},
        BadCase{"not_gltf2.gltf", "version 1.0"}, BadCase{"duplicate_key.gltf", "nodes[0]: duplicate key 'mesh'"},
        BadCase{"glb_length_beyond_file.glb", "declares"}, BadCase{"glb_json_chunk_huge.glb", "JSON chunk length"},
        BadCase{"glb_bin_chunk_huge.glb", "BIN chunk length"}, BadCase{"glb_bin_chunk_plus8.glb", "BIN chunk length"},
        BadCase{"glb_missing_bin.glb", "no BIN chunk"}, BadCase{"glb_truncated.glb", "declares"},
        BadCase{"empty.glb", "empty file"}, BadCase{"empty.gltf", "empty file"}),
    [](const ::testing::TestParamInfo<BadCase>& info) {
      std::string name = info.param.file;
      for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return name;
    });

TEST(SceneGltf, SandboxNeverReadsOutsideTheFolder) {
  // The same bytes one folder up exist (tests/data/scene/../scene/cube.bin), so only the
  // sandbox stops this load.
  test::TempDir dir;
  std::ifstream in(sceneData("uri_percent_parent.gltf"));
  std::stringstream text;
  text << in.rdbuf();
  const std::string path = dir.file("inner/model.gltf", text.str());
  dir.file("scene/cube.bin", "not read");
  expectError([&] { detail::loadGltf(path); }, path, "leaves its folder");
}

// Deterministic mutation smoke test: corrupted copies of valid files either load or throw
// penumbra::Error; under ASan/UBSan this is the memory-safety net for the checks above.
TEST(SceneGltf, MutatedFilesNeverCrash) {
  test::TempDir dir;
  std::uint32_t state = 12345;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  };
  const char kDigits[] = "0123456789-.e,[]{}\"";
  int loaded = 0, rejected = 0;
  for (const char* name : {"cube.glb", "cube.gltf", "materials.gltf", "lights.gltf"}) {
    std::ifstream in(sceneData(name), std::ios::binary);
    const std::string original((std::istreambuf_iterator<char>(in)), {});
    const bool binary = std::string(name).ends_with(".glb");
    for (int round = 0; round < 150; ++round) {
      std::string bytes = original;
      const int edits = 1 + int(next() % 4);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = next() % bytes.size();
        bytes[at] = binary ? char(next() & 0xff) : kDigits[next() % (sizeof(kDigits) - 1)];
      }
      if (next() % 8 == 0) bytes.resize(next() % bytes.size());
      const std::string path = dir.file(std::string("m") + (binary ? ".glb" : ".gltf"), bytes);
      try {
        detail::loadGltf(path);
        ++loaded;
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        ++rejected;
      } catch (const std::exception& e) {
        ADD_FAILURE() << name << " round " << round << ": " << e.what();
      }
    }
  }
  EXPECT_GT(rejected, 0);
  EXPECT_GT(loaded, 0);
}

// --- assimp-testmodels

TEST(SceneGltf, AssimpModelsLoad) {
  if (!std::filesystem::is_directory(kAssimpGltf))
    FAIL() << "assimp-testmodels not installed (./setup.sh --deps installs it)";
  const std::string dir = kAssimpGltf;
  const Scene engine = loadScene(dir + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  // 75,730 distinct triangles, instanced by 82 nodes into 121,496, of which the file's
  // repeated-index triangles are dropped and counted. The bare-file scene adds a floor.
  std::size_t kept = 0, dropped = 0;
  for (const SceneMesh& m : engine.meshes) {
    kept += m.mesh.triangles.size();
    dropped += m.report.droppedTotal();
  }
  EXPECT_EQ(kept + dropped, 121496u + 2u);
  EXPECT_GT(engine.triangleCount(), 75000u);
  for (const char* box : {"/BoxTextured-glTF/BoxTextured.gltf", "/BoxTextured-glTF-Binary/BoxTextured.glb",
                          "/BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    SCOPED_TRACE(box);
    const Scene s = loadScene(dir + box);
    EXPECT_EQ(s.triangleCount(), 12u + 2u);
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].image.width, 211);
    EXPECT_EQ(s.textures[0].image.channels, 4);
    ASSERT_GE(s.lights.size(), 1u);
  }
}

TEST(SceneGltf, AssimpMalformedModelsAreRejected) {
  if (!std::filesystem::is_directory(kAssimpGltf))
    FAIL() << "assimp-testmodels not installed (./setup.sh --deps installs it)";
  const std::string dir = kAssimpGltf;
  for (const char* bad : {"/RecursiveNodes/RecursiveNodes.gltf", "/MissingBin/BoxTextured.gltf",
                          "/TestNoRootNode/NoScene.gltf", "/IndexOutOfRange/AllIndicesOutOfRange.gltf"}) {
    const std::string path = dir + bad;
    expectError([&] { loadScene(path); }, path, "");
  }
}

TEST(SceneGltf, AssimpInfinitesAreCounted) {
  // Every vertex of this box has an infinite coordinate: all 12 triangles are dropped and the
  // error says why.
  const std::string path = std::string(kAssimpGltf) + "/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb";
  if (!std::filesystem::exists(path)) FAIL() << "assimp-testmodels not installed (./setup.sh --deps installs it)";
  expectError([&] { detail::loadGltf(path); }, path, "12 with non-finite positions");
}

TEST(SceneGltf, NonFinitePositionsDroppedAndCounted) {
  // Vertex 7 of the cube is infinite: the 6 triangles using it are dropped and counted.
  const detail::Model m = load("cube_one_infinite.gltf");
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_EQ(m.meshes[0].report.droppedNonFinite, 6u);
  EXPECT_EQ(m.meshes[0].mesh.triangles.size(), 6u);
  EXPECT_TRUE(warned(m, "6 with non-finite positions"));
}

// The asset generator's mode files draw the same quad as TRIANGLES, strips and fans, with and
// without indices: all must face the same way once converted.
TEST(SceneGltf, AssimpPrimitiveModesAgree) {
  const std::string dir = std::string(kAssimpGltf) + "/glTF-Asset-Generator/Mesh_PrimitiveMode/";
  if (!std::filesystem::is_directory(dir)) FAIL() << "assimp-testmodels not installed (./setup.sh --deps installs it)";
  for (const char* n : {"04", "05", "06", "11", "12", "13"}) {
    SCOPED_TRACE(n);
    const detail::Model m = detail::loadGltf(dir + "Mesh_PrimitiveMode_" + n + ".gltf");
    ASSERT_EQ(triangles(m), 2u);
    for (const glm::uvec3& t : m.meshes[0].mesh.triangles) {
      const auto& p = m.meshes[0].mesh.positions;
      EXPECT_GT(glm::cross(p[t.y] - p[t.x], p[t.z] - p[t.x]).z, 0.0f);
    }
  }
}

// Every file in the folder: loads, or fails with one penumbra::Error naming it. Never a crash
// or another exception type.
TEST(SceneGltf, AssimpWholeFolderWalk) {
  if (!std::filesystem::is_directory(kAssimpGltf))
    FAIL() << "assimp-testmodels not installed (./setup.sh --deps installs it)";
  int loaded = 0, rejected = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kAssimpGltf)) {
    const std::string ext = detail::lowerExtension(entry.path().string());
    if (ext != ".gltf" && ext != ".glb") continue;
    const std::string path = entry.path().string();
    try {
      const Scene s = loadScene(path);
      EXPECT_GT(s.triangleCount(), 0u) << path;
      if (std::getenv("PENUMBRA_TEST_VERBOSE")) {
        std::printf("loaded   %s: %zu triangles, %zu warnings\n", path.c_str(), s.triangleCount(), s.warnings.size());
      }
      ++loaded;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      if (std::getenv("PENUMBRA_TEST_VERBOSE")) std::printf("rejected %s\n", e.what());
      ++rejected;
    } catch (const std::exception& e) {
      ADD_FAILURE() << path << ": unexpected exception: " << e.what();
    }
  }
  EXPECT_GE(loaded, 20);
  EXPECT_GE(rejected, 5);
  std::printf("[          ] assimp glTF2: %d loaded, %d rejected\n", loaded, rejected);
}

}  // namespace
}  // namespace penumbra
