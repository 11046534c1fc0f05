// Procedural shapes, mesh/light placement and the Light/Scene queries.
#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/loaders.h"
#include "scene_test_util.h"

namespace penumbra {
namespace {

using test::signedVolume;

// Every face's normal points away from `centre` (convex shapes only).
void expectOutward(const geo::TriangleMesh& m, glm::vec3 centre) {
  for (const glm::uvec3& t : m.triangles) {
    const glm::vec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
    ASSERT_GT(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - centre), 0.0f);
  }
}

geo::MeshReport clean(geo::TriangleMesh m) {
  geo::MeshReport r;
  geo::cleanMesh(m, r);
  return r;
}

TEST(SceneShapes, Box) {
  const geo::TriangleMesh m = detail::makeBox({1.0f, 2.0f, 3.0f});
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_NEAR(signedVolume(m), 6.0, 1e-5);
  expectOutward(m, glm::vec3(0.0f));
  const geo::MeshReport r = clean(m);
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.droppedTotal(), 0u);
}

TEST(SceneShapes, Sphere) {
  const geo::TriangleMesh m = detail::makeSphere(0.5f, 32, 16);
  EXPECT_EQ(m.triangles.size(), 2u * 32u * 15u);
  EXPECT_NEAR(signedVolume(m), 4.0 / 3.0 * glm::pi<double>() * 0.125, 0.02);
  expectOutward(m, glm::vec3(0.0f));
  ASSERT_EQ(m.normals.size(), m.positions.size());
  EXPECT_NEAR(glm::dot(m.normals[5], glm::normalize(m.positions[5])), 1.0f, 1e-5f);
  EXPECT_TRUE(clean(m).closed);
}

TEST(SceneShapes, CylinderCapsAndOpenBottom) {
  const geo::TriangleMesh closed = detail::makeCylinder(0.5f, 2.0f, 24, true, true);
  EXPECT_EQ(closed.triangles.size(), 4u * 24u);
  EXPECT_NEAR(signedVolume(closed), glm::pi<double>() * 0.25 * 2.0, 0.05);
  expectOutward(closed, glm::vec3(0.0f));
  EXPECT_TRUE(clean(closed).closed);

  const geo::TriangleMesh open = detail::makeCylinder(0.5f, 2.0f, 24, true, false);
  EXPECT_EQ(open.triangles.size(), 3u * 24u);
  expectOutward(open, glm::vec3(0.0f));
  const geo::MeshReport r = clean(open);
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.openEdges, 24u);
  EXPECT_EQ(r.inconsistentEdges, 0u);

  const geo::MeshReport tube = clean(detail::makeCylinder(0.5f, 2.0f, 24, false, false));
  EXPECT_EQ(tube.openEdges, 48u);
}

TEST(SceneShapes, QuadAndDiskFaceUp) {
  for (const geo::TriangleMesh& m : {detail::makeQuad(glm::vec2(2.0f, 1.0f)), detail::makeDisk(0.5f, 16)}) {
    for (const glm::uvec3& t : m.triangles) {
      const glm::vec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
      EXPECT_GT(glm::cross(b - a, c - a).y, 0.0f);
    }
    EXPECT_EQ(m.uvs.size(), m.positions.size());
  }
  EXPECT_EQ(clean(detail::makeQuad(glm::vec2(1.0f))).openEdges, 4u);
  EXPECT_EQ(clean(detail::makeDisk(0.5f, 16)).openEdges, 16u);
}

TEST(SceneShapes, MirroringTransformKeepsWindingOutward) {
  geo::TriangleMesh m = detail::makeBox(glm::vec3(1.0f));
  detail::transformMesh(m, glm::scale(glm::mat4(1.0f), {-1.0f, 2.0f, 1.0f}));
  EXPECT_NEAR(signedVolume(m), 2.0, 1e-5);
  expectOutward(m, glm::vec3(0.0f));
}

TEST(SceneShapes, TransformLightScalesAndTurns) {
  Light l;
  l.size = {1.0f, 2.0f};
  const glm::mat4 m = glm::translate(glm::mat4(1.0f), {0, 1, 0}) *
                      glm::rotate(glm::mat4(1.0f), glm::half_pi<float>(), {0, 0, 1}) *
                      glm::scale(glm::mat4(1.0f), {3.0f, 1.0f, 1.0f});
  const Light t = detail::transformLight(l, m);
  EXPECT_NEAR(glm::distance(t.position, glm::vec3(-4, 1, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(t.normal, glm::vec3(1, 0, 0)), 0.0f, 1e-5f);  // -Y turned by Rz
  EXPECT_NEAR(t.size.x, 3.0f, 1e-5f);
  EXPECT_NEAR(t.size.y, 2.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(t.normal, t.tangent), 0.0f, 1e-5f);
}

TEST(SceneShapes, LightArea) {
  Light l;
  l.shape = LightShape::Rect;
  l.size = {2.0f, 3.0f};
  EXPECT_FLOAT_EQ(l.area(), 6.0f);
  l.shape = LightShape::Disk;
  l.size = {2.0f, 0.0f};
  EXPECT_FLOAT_EQ(l.area(), 4.0f * glm::pi<float>());
  l.shape = LightShape::Sphere;
  EXPECT_FLOAT_EQ(l.area(), 16.0f * glm::pi<float>());
  l.shape = LightShape::Point;
  EXPECT_EQ(l.area(), 0.0f);
  EXPECT_FALSE(l.isArea());
}

TEST(SceneShapes, LightFrameAt) {
  Light l;
  EXPECT_EQ(l.frameAt(1.0f), -1);
  l.emissionFrames = {4, 5, 6};
  l.fps = 0.0f;
  EXPECT_EQ(l.frameAt(10.0f), 0);
  l.fps = 2.0f;
  EXPECT_EQ(l.frameAt(0.0f), 0);
  EXPECT_EQ(l.frameAt(0.49f), 0);
  EXPECT_EQ(l.frameAt(0.5f), 1);
  EXPECT_EQ(l.frameAt(1.2f), 2);
  EXPECT_EQ(l.frameAt(1.5f), 0);    // wraps
  EXPECT_EQ(l.frameAt(-0.25f), 2);  // floor(-0.5) = -1 -> 2
  EXPECT_EQ(l.frameAt(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(SceneShapes, SceneQueries) {
  Scene s;
  s.materials.resize(2);
  s.materials[1].opacity = 0.5f;
  SceneMesh a;
  a.mesh = detail::makeBox(glm::vec3(1.0f));
  a.mesh.positions.push_back(glm::vec3(std::numeric_limits<float>::quiet_NaN()));  // unused
  s.meshes.push_back(a);
  EXPECT_EQ(s.triangleCount(), 12u);
  EXPECT_FALSE(s.hasSemiOpaque());
  glm::vec3 lo, hi;
  s.bounds(lo, hi);
  EXPECT_EQ(lo, glm::vec3(-0.5f));
  EXPECT_EQ(hi, glm::vec3(0.5f));
  s.meshes[0].material = 1;
  EXPECT_TRUE(s.hasSemiOpaque());
  Scene empty;
  empty.bounds(lo, hi);
  EXPECT_EQ(lo, glm::vec3(0.0f));
  EXPECT_EQ(hi, glm::vec3(0.0f));
}

}  // namespace
}  // namespace penumbra
