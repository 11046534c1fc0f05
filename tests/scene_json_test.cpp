// The scene description format: shapes, transforms, materials, lights, camera, unknown keys,
// --set overrides, file references, bare geometry files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <sstream>

#include "scene/loaders.h"
#include "scene_test_util.h"

namespace penumbra {
namespace {

using test::expectError;
using test::hasWarning;
using test::TempDir;

glm::vec3 boundsLo(const SceneMesh& m) {
  Scene s;
  s.meshes.push_back(m);
  glm::vec3 lo, hi;
  s.bounds(lo, hi);
  return lo;
}

glm::vec3 boundsHi(const SceneMesh& m) {
  Scene s;
  s.meshes.push_back(m);
  glm::vec3 lo, hi;
  s.bounds(lo, hi);
  return hi;
}

void expectNear(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
  EXPECT_LT(glm::distance(a, b), eps) << "(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y
                                      << ", " << b.z << ")";
}

constexpr const char* kAllShapes = R"({
  // comments are allowed
  "name": "all",
  "camera": {"position": [0, 2, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 50, "near": 0.1},
  "resolution": [320, 200],
  "background": 0.25,
  "materials": [{"name": "glass", "baseColor": [0.2, 0.4, 0.6], "opacity": 0.5},
                {"name": "red", "baseColor": [1, 0, 0]},
                {"name": "gloss", "roughness": 0.25}],
  "objects": [
    {"name": "box", "shape": "box", "size": [1, 2, 3], "translate": [10, 0, 0]},
    {"name": "plane", "shape": "plane", "material": "red"},
    {"name": "quad", "shape": "quad", "size": [2, 1], "rotate": [90, 0, 0]},
    {"name": "corners", "shape": "quad", "corners": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]},
    {"name": "sphere", "shape": "sphere", "radius": 2, "segments": 8, "rings": 4,
     "scale": [1, 0.5, 1]},
    {"name": "cylinder", "shape": "cylinder", "radius": 1, "height": 2, "segments": 8,
     "caps": "top"},
    {"name": "tube", "shape": "cylinder", "segments": 8, "caps": "none"},
    {"name": "openbottom", "shape": "cylinder", "segments": 8, "open_bottom": true},
    {"name": "disk", "shape": "disk", "radius": 1, "segments": 12, "material": "glass"},
    {"name": "axis", "shape": "box", "rotate": {"axis": [0, 0, 1], "angle": 90},
     "scale": [2, 1, 1]},
    {"name": "matrix", "shape": "box", "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 5,6,7,1], "scale": 2},
    {"name": "ghost", "shape": "box", "material": "red", "opacity": 0.25}
  ],
  "lights": [
    {"name": "rect", "type": "rect", "position": [0, 4, 0], "target": [0, 0, 0], "up": [0, 0, -1],
     "size": [2, 1], "color": [1, 0.5, 0.25], "intensity": 3},
    {"name": "disk", "type": "disk", "position": [1, 4, 0], "normal": [0, -1, 0], "radius": 0.3},
    {"name": "sphere", "type": "sphere", "position": [2, 4, 0], "radius": 0.2},
    {"name": "point", "type": "point", "position": [3, 4, 0], "intensity": 100},
    {"name": "tex", "type": "rect", "size": 1, "texture": "procedural:stained-glass"},
    {"name": "anim", "type": "rect", "fps": 4,
     "frames": ["procedural:stained-glass", "procedural:stained-glass"]}
  ]
})";

const SceneMesh& mesh(const Scene& s, const std::string& name) {
  for (const SceneMesh& m : s.meshes) {
    if (m.name == name) return m;
  }
  throw std::runtime_error("no mesh " + name);
}

TEST(SceneJson, AllShapesAndTransforms) {
  TempDir dir;
  const std::string path = dir.file("all.json", kAllShapes);
  const Scene s = loadScene(path);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_EQ(s.name, "all");
  EXPECT_EQ(s.sourcePath, path);
  EXPECT_EQ(s.width, 320);
  EXPECT_EQ(s.height, 200);
  EXPECT_EQ(s.background, glm::vec3(0.25f));
  EXPECT_EQ(s.camera.fovY, 50.0f);
  EXPECT_EQ(s.camera.zNear, 0.1f);

  expectNear(boundsLo(mesh(s, "box")), {9.5f, -1.0f, -1.5f});
  expectNear(boundsHi(mesh(s, "plane")), {5.0f, 0.0f, 5.0f});
  // 90 degrees about X turns the XZ quad into the XY plane facing -Z... +Y -> +Z.
  expectNear(boundsHi(mesh(s, "quad")), {1.0f, 0.5f, 0.0f});
  EXPECT_EQ(mesh(s, "sphere").mesh.triangles.size(), 2u * 8u * 3u);
  expectNear(boundsHi(mesh(s, "sphere")), {2.0f, 1.0f, 2.0f}, 1e-4f);
  EXPECT_EQ(mesh(s, "cylinder").mesh.triangles.size(), 3u * 8u);
  EXPECT_EQ(mesh(s, "tube").mesh.triangles.size(), 2u * 8u);
  EXPECT_EQ(mesh(s, "openbottom").mesh.triangles.size(), 3u * 8u);
  EXPECT_EQ(mesh(s, "openbottom").report.openEdges, 8u);
  EXPECT_EQ(mesh(s, "disk").mesh.triangles.size(), 12u);
  EXPECT_EQ(mesh(s, "corners").mesh.triangles.size(), 2u);
  // Scale (2,1,1) then 90 degrees about Z: 1 wide, 2 tall.
  expectNear(boundsHi(mesh(s, "axis")), {0.5f, 1.0f, 0.5f});
  // T R S M: the matrix translation is scaled by 2 too.
  expectNear(boundsLo(mesh(s, "matrix")), {9.0f, 11.0f, 13.0f});
  EXPECT_TRUE(mesh(s, "box").report.closed);

  const Material& glass = s.materials[std::size_t(mesh(s, "disk").material)];
  EXPECT_EQ(glass.name, "glass");
  EXPECT_EQ(glass.opacity, 0.5f);
  EXPECT_EQ(glass.alphaMode, AlphaMode::Blend);
  const Material& ghost = s.materials[std::size_t(mesh(s, "ghost").material)];
  EXPECT_EQ(ghost.baseColor, glm::vec3(1, 0, 0));
  EXPECT_EQ(ghost.opacity, 0.25f);
  EXPECT_EQ(s.materials[std::size_t(mesh(s, "plane").material)].opacity, 1.0f);
  // "metallic" or "roughness" selects the metallic-roughness BRDF; without them, Lambertian.
  EXPECT_EQ(glass.brdf, BrdfModel::Lambert);
  const auto gloss = std::find_if(s.materials.begin(), s.materials.end(), [](auto& m) { return m.name == "gloss"; });
  ASSERT_NE(gloss, s.materials.end());
  EXPECT_EQ(gloss->brdf, BrdfModel::MetallicRoughness);
  EXPECT_EQ(gloss->roughness, 0.25f);
  EXPECT_EQ(gloss->metallic, 0.0f);
  EXPECT_EQ(mesh(s, "box").material, 0);  // the default material
  EXPECT_TRUE(s.hasSemiOpaque());

  ASSERT_EQ(s.lights.size(), 6u);
  const Light& rect = s.lights[0];
  EXPECT_EQ(rect.shape, LightShape::Rect);
  expectNear(rect.normal, {0, -1, 0});
  expectNear(rect.bitangent(), {0, 0, -1});  // follows "up"
  EXPECT_EQ(rect.size, glm::vec2(2, 1));
  EXPECT_EQ(rect.color, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_EQ(rect.intensity, 3.0f);
  EXPECT_EQ(s.lights[1].shape, LightShape::Disk);
  EXPECT_FLOAT_EQ(s.lights[1].size.x, 0.3f);
  EXPECT_EQ(s.lights[2].shape, LightShape::Sphere);
  EXPECT_EQ(s.lights[3].shape, LightShape::Point);
  ASSERT_EQ(s.lights[4].emissionFrames.size(), 1u);
  ASSERT_EQ(s.lights[5].emissionFrames.size(), 2u);
  EXPECT_EQ(s.lights[5].fps, 4.0f);
  EXPECT_EQ(s.lights[5].frameAt(0.3f), 1);
  EXPECT_EQ(s.textures.size(), 1u);  // the same texture is loaded once
}

// Quarter turns are exact: a plane turned over by [180, 0, 0] (a ceiling) lies exactly in its
// plane (float radians gave sin 8.7e-8: 2e-7 off at 2.5 from the axis, and a light placed on the
// ceiling lay behind it within rounding), -90 and 450 too; other angles as glm::rotate.
TEST(SceneJson, QuarterTurnsAreExact) {
  TempDir dir;
  const std::string path = dir.file("turns.json", R"({
    "objects": [
      {"name": "ceiling", "shape": "plane", "size": 5, "rotate": [180, 0, 0], "translate": [1.5, 1.5, -1.5]},
      {"name": "wall", "shape": "plane", "size": 2, "rotate": [0, 450, -90]},
      {"name": "axis", "shape": "plane", "size": 2, "rotate": {"axis": [1, 0, 0], "angle": -270}},
      {"name": "tilted", "shape": "plane", "size": 2, "rotate": [30, 0, 0]}
    ],
    "lights": [{"type": "point", "position": [0, 3, 0]}]
  })");
  const Scene s = loadScene(path);
  for (const glm::vec3& p : mesh(s, "ceiling").mesh.positions) EXPECT_EQ(p.y, 1.5f);
  for (const glm::vec3& p : mesh(s, "wall").mesh.positions) EXPECT_EQ(p.x, 0.0f);
  for (const glm::vec3& p : mesh(s, "axis").mesh.positions) EXPECT_EQ(p.z, 0.0f);
  const glm::mat4 r = glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(1, 0, 0));
  const std::vector<glm::vec3>& tilted = mesh(s, "tilted").mesh.positions;
  ASSERT_FALSE(tilted.empty());
  for (const glm::vec3& p : tilted) EXPECT_NEAR((glm::inverse(r) * glm::vec4(p, 1.0f)).y, 0.0f, 1e-6f);
}

TEST(SceneJson, UnknownKeysWarnWithTheirPath) {
  TempDir dir;
  const std::string path = dir.file("u.json", R"({
    "colour": 1,
    "camera": {"fov": 40, "fovy": 2},
    "objects": [{"shape": "box", "sise": 2}],
    "lights": [{"type": "point", "size": [1, 1]}]
  })");
  const Scene s = loadScene(path);
  EXPECT_TRUE(hasWarning(s, path + ": scene: unknown key 'colour'"));
  EXPECT_TRUE(hasWarning(s, "camera: unknown key 'fovy'"));
  EXPECT_TRUE(hasWarning(s, "objects[0]: unknown key 'sise'"));
  EXPECT_TRUE(hasWarning(s, "lights[0]: unknown key 'size'"));  // points have no size
  EXPECT_EQ(s.warnings.size(), 4u);
}

TEST(SceneJson, Overrides) {
  TempDir dir;
  const std::string path = dir.file("o.json", kAllShapes);
  const Scene s = loadScene(path, {"camera.fov=30", "lights.0.size=[3,4]", "objects.0.translate.1=5", "name=renamed",
                                   "objects.1.material=\"glass\"", "lights.0.color=2", "background=[0,0,1]"});
  EXPECT_EQ(s.camera.fovY, 30.0f);
  EXPECT_EQ(s.lights[0].size, glm::vec2(3, 4));
  expectNear(boundsLo(mesh(s, "box")), {9.5f, 4.0f, -1.5f});
  EXPECT_EQ(s.name, "renamed");  // not JSON: taken as a string
  EXPECT_EQ(s.materials[std::size_t(mesh(s, "plane").material)].name, "glass");
  EXPECT_EQ(s.lights[0].color, glm::vec3(2.0f));
  EXPECT_EQ(s.background, glm::vec3(0, 0, 1));

  // A new key is created, then reported as unknown like any other.
  const Scene created = loadScene(path, {"objects.0.bogus.deep=1", "extra=1"});
  EXPECT_TRUE(hasWarning(created, "objects[0] 'box': unknown key 'bogus'"));
  EXPECT_TRUE(hasWarning(created, "unknown key 'extra'"));

  expectError([&] { loadScene(path, {"lights.9.size=1"}); }, "override", "index 9 out of range");
  expectError([&] { loadScene(path, {"lights.x.size=1"}); }, "override", "is not an index");
  expectError([&] { loadScene(path, {"camera.fov.x=1"}); }, "override", "'camera.fov' is number");
  expectError([&] { loadScene(path, {"camera.fov"}); }, "override", "expected key=value");
  expectError([&] { loadScene(path, {"camera..fov=1"}); }, "override", "empty path component");
  expectError([&] { loadScene(path, {"camera.fov=nan"}); }, path, "camera.fov: expected a number");
}

TEST(SceneJson, ValidationErrorsNameTheFileAndTheItem) {
  TempDir dir;
  auto scene = [&](const std::string& lights, const std::string& extra = "") {
    return dir.file("v.json", R"({"objects": [{"shape": "box"}], "lights": [)" + lights + "]" + extra + "}");
  };
  std::string p = scene(R"({"name": "key", "type": "rect", "size": [0, 1]})");
  expectError([&] { loadScene(p); }, p, "lights[0] 'key'.size: an area light needs a positive size");
  p = scene(R"({"name": "d", "type": "disk", "radius": -1})");
  expectError([&] { loadScene(p); }, p, "lights[0] 'd'.radius");
  p = scene(R"({"type": "rect", "position": [0, 1, 0], "target": [0, 1, 0]})");
  expectError([&] { loadScene(p); }, p, "must be a non-zero vector");
  p = scene(R"({"type": "rect", "normal": [0, -1, 0], "tangent": [0, 2, 0]})");
  expectError([&] { loadScene(p); }, p, "projected onto the light's plane");
  p = scene(R"({"type": "tube"})");
  expectError([&] { loadScene(p); }, p, "unknown light type 'tube'");
  p = scene(R"({"type": "rect", "frames": ["procedural:stained-glass", "procedural:stained-glass"]})");
  expectError([&] { loadScene(p); }, p, "needs \"fps\" > 0");
  p = scene(R"({"type": "rect", "intensity": 1e39})");
  expectError([&] { loadScene(p); }, p, "not a finite number");
  p = scene("{}", R"(, "camera": {"position": [0, 0, 0], "target": [0, 0, 0]})");
  expectError([&] { loadScene(p); }, p, "camera: position and target coincide");
  p = scene("{}", R"(, "camera": {"position": [0, 5, 0], "target": [0, 0, 0]})");
  expectError([&] { loadScene(p); }, p, "parallel to the viewing direction");
  p = scene("{}", R"(, "camera": {"fov": 180})");
  expectError([&] { loadScene(p); }, p, "camera.fov");
  p = scene("{}", R"(, "resolution": [0, 10])");
  expectError([&] { loadScene(p); }, p, "resolution");

  auto object = [&](const std::string& o) { return dir.file("o.json", R"({"objects": [)" + o + "]}"); };
  p = object(R"({"shape": "cube"})");
  expectError([&] { loadScene(p); }, p, "unknown shape 'cube'");
  p = object(R"({"shape": "box", "scale": [1, 0, 1]})");
  expectError([&] { loadScene(p); }, p, "singular");
  p = object(R"({"shape": "box", "material": "nope"})");
  expectError([&] { loadScene(p); }, p, "unknown material 'nope'");
  p = object(R"({"shape": "box", "opacity": 1.5})");
  expectError([&] { loadScene(p); }, p, "opacity");
  p = dir.file("m.json", R"({"materials": [{"name": "m", "roughness": 1.5}], "objects": [{"shape": "box"}]})");
  expectError([&] { loadScene(p); }, p, "materials[0] 'm'.roughness: must be in [0, 1], got 1.5");
  p = dir.file("m.json", R"({"materials": [{"name": "m", "metallic": -0.5}], "objects": [{"shape": "box"}]})");
  expectError([&] { loadScene(p); }, p, "materials[0] 'm'.metallic: must be in [0, 1]");
  p = dir.file("m.json", R"({"materials": [{"name": "m", "alphaCutoff": 0.5}], "objects": [{"shape": "box"}]})");
  expectError([&] { loadScene(p); }, p, "materials[0] 'm'.alphaCutoff: needs a \"texture\" whose alpha it tests");
  p = dir.file("m.json", R"({"materials": [{"name": "m", "alphaCutoff": 0}], "objects": [{"shape": "box"}]})");
  expectError([&] { loadScene(p); }, p, "materials[0] 'm'.alphaCutoff: must be in (0, 1]");
  p = object(R"({"shape": "sphere", "segments": 2})");
  expectError([&] { loadScene(p); }, p, "segments");
  p = object(R"({"name": "x"})");
  expectError([&] { loadScene(p); }, p, "objects[0] 'x': an object needs \"file\" or \"shape\"");
  p = object(R"({"file": "../escape.obj"})");
  expectError([&] { loadScene(p); }, p, "leaves its folder");
  p = object(R"({"file": "/etc/passwd"})");
  expectError([&] { loadScene(p); }, p, "absolute path");
  p = object(R"({"file": "missing.obj"})");
  expectError([&] { loadScene(p); }, p, "'missing.obj' not found");
  p = object(R"({"shape": "box", "translate": [1, 2]})");
  expectError([&] { loadScene(p); }, p, "objects[0].translate: expected 3 numbers");

  p = dir.file("bad.json", "{\"objects\": [\n  {\"shape\": \"box\",}\n]}");
  expectError([&] { loadScene(p); }, p, "invalid JSON");
  p = dir.file("list.json", "[1, 2]");
  expectError([&] { loadScene(p); }, p, "JSON object");
  expectError([&] { loadScene(dir.path() + "/none.json"); }, dir.path() + "/none.json", "no such file");
  p = dir.file("x.txt", "");
  expectError([&] { loadScene(p); }, p, "unsupported scene file");
}

TEST(SceneJson, CameraFramesTheSceneWhenMissing) {
  TempDir dir;
  const std::string p = dir.file("c.json", R"({"objects": [{"shape": "box", "translate": [3, 0, 0]}],
                                              "lights": [{"type": "point"}]})");
  const Scene s = loadScene(p);
  expectNear(s.camera.target, {3, 0, 0});
  EXPECT_GT(glm::distance(s.camera.position, s.camera.target), 1.0f);
}

TEST(SceneJson, FileObjectsAreInstanced) {
  TempDir dir;
  dir.file("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string p = dir.file("f.json", R"({
    "materials": [{"name": "m", "baseColor": 0.5}],
    "objects": [{"name": "a", "file": "tri.obj", "material": "m"},
                {"name": "b", "file": "tri.obj", "scale": [-1, 1, 1], "opacity": 0.5}],
    "lights": [{"type": "point"}]})");
  const Scene s = loadScene(p);
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.materials[std::size_t(s.meshes[0].material)].name, "m");
  EXPECT_EQ(s.materials[std::size_t(s.meshes[1].material)].opacity, 0.5f);
  // The mirrored copy keeps facing +Z.
  for (const SceneMesh& m : s.meshes) {
    const auto& q = m.mesh.positions;
    const glm::uvec3 t = m.mesh.triangles[0];
    EXPECT_GT(glm::cross(q[t.y] - q[t.x], q[t.z] - q[t.x]).z, 0.0f) << m.name;
  }
}

TEST(SceneJson, BareGeometryFileGetsFloorCameraAndLight) {
  TempDir dir;
  const std::string p = dir.file("tet.obj",
                                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                 "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const Scene s = loadScene(p, {"camera.fov=20"});
  EXPECT_EQ(s.name, "tet");
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_TRUE(s.meshes[0].report.closed);
  glm::vec3 lo, hi;
  s.bounds(lo, hi);
  EXPECT_LT(lo.y, 0.0f);  // the floor, just below the model
  EXPECT_GT(lo.y, -0.01f);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].shape, LightShape::Rect);
  EXPECT_GT(s.lights[0].position.y, 1.0f);
  expectNear(s.camera.target, {0.5f, 0.5f, 0.5f});
  EXPECT_EQ(s.camera.fovY, 20.0f);
  EXPECT_TRUE(s.warnings.empty());
}

TEST(SceneJson, OverridePathRules) {
  detail::Json doc = detail::Json::parse(R"({"a": [1, {"b": 2}], "s": "x"})");
  detail::applyOverrides(doc, {"a.1.b=[1,2]", "a.0=\"str\"", "new.key.path=true", "s=hello world"});
  EXPECT_EQ(doc["a"][1]["b"], detail::Json::parse("[1,2]"));
  EXPECT_EQ(doc["a"][0], "str");
  EXPECT_EQ(doc["new"]["key"]["path"], true);
  EXPECT_EQ(doc["s"], "hello world");
  detail::applyOverrides(doc, {"v="});
  EXPECT_EQ(doc["v"], "");
}

TEST(SceneJson, RelativePathRules) {
  using detail::relativePathProblem;
  EXPECT_EQ(relativePathProblem("a/b.obj"), "");
  EXPECT_EQ(relativePathProblem("./a b.obj"), "");
  EXPECT_NE(relativePathProblem(""), "");
  EXPECT_NE(relativePathProblem("../a"), "");
  EXPECT_NE(relativePathProblem("a/../../b"), "");
  EXPECT_NE(relativePathProblem("/a"), "");
  EXPECT_NE(relativePathProblem("C:/a"), "");
  EXPECT_NE(relativePathProblem("https://x/y"), "");
  EXPECT_NE(relativePathProblem("a$(rm)"), "");
  EXPECT_NE(relativePathProblem("a`b`"), "");
  EXPECT_NE(relativePathProblem("a\\b"), "");
  EXPECT_NE(relativePathProblem(std::string("a\0b", 3)), "");
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// The complete example in docs/scene-format.md loads, given the files it names.
TEST(SceneJson, DocumentedExampleLoads) {
  std::ifstream in(test::sourcePath("docs/scene-format.md"));
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::size_t start = doc.find("```json\n");
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = doc.find("```", start + 8);
  TempDir dir;
  const std::string path = dir.file("example.json", doc.substr(start + 8, end - start - 8));
  namespace fs = std::filesystem;
  const fs::path png = test::sourcePath("scenes/textures/stained-glass.png");
  fs::create_directories(dir.path() + "/textures");
  fs::create_directories(dir.path() + "/models");
  for (const char* name : {"wood.png", "f0.png", "f1.png", "f2.png"}) {
    fs::copy_file(png, dir.path() + "/textures/" + name);
  }
  fs::copy_file(test::sceneData("cube.glb"), dir.path() + "/models/teapot.glb");
  if (!fs::is_directory("/usr/share/assimp/models"))
    FAIL() << "assimp-testmodels not installed (./setup.sh --deps installs it)";
  const Scene s = loadScene(path, {"lights.0.size=[3,1.5]", "objects.2.translate.1=1"});
  for (const std::string& w : s.warnings) EXPECT_EQ(w.find("example.json"), std::string::npos) << w;
  EXPECT_EQ(s.lights.size(), 5u);
  EXPECT_EQ(s.lights[1].emissionFrames.size(), 3u);
  EXPECT_EQ(s.lights[0].size, glm::vec2(3.0f, 1.5f));
  EXPECT_TRUE(s.hasSemiOpaque());
}

}  // namespace
}  // namespace penumbra
