// cleanMesh, buildEdgeTopology and extractPointSilhouette on meshes small enough to check by
// hand, plus a randomized comparison against a brute-force silhouette.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "geometry/mesh.h"
#include "geometry/silhouette.h"
#include "geometry_test_meshes.h"

namespace penumbra::geo {
namespace {

using test::book;
using test::cube;
using EdgeSet = std::set<std::pair<std::uint32_t, std::uint32_t>>;

// Quad in the y = 0 plane, normal +y.
TriangleMesh openQuad() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// Icosphere with every vertex pushed to a random radius: closed, consistently wound, and
// with no two faces coplanar by accident.
TriangleMesh bumpySphere(int subdivisions, std::mt19937& rng) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  TriangleMesh m;
  m.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto [it, added] = mid.try_emplace(key, static_cast<std::uint32_t>(m.positions.size()));
      if (added) m.positions.push_back(0.5f * (m.positions[a] + m.positions[b]));
      return it->second;
    };
    std::vector<glm::uvec3> next;
    for (const glm::uvec3& tri : m.triangles) {
      const std::uint32_t ab = midpoint(tri.x, tri.y), bc = midpoint(tri.y, tri.z), ca = midpoint(tri.z, tri.x);
      next.insert(next.end(), {{tri.x, ab, ca}, {tri.y, bc, ab}, {tri.z, ca, bc}, {ab, bc, ca}});
    }
    m.triangles = std::move(next);
  }
  std::uniform_real_distribution<float> radius(0.9f, 1.1f);
  for (glm::vec3& p : m.positions) p = glm::normalize(p) * radius(rng);
  return m;
}

// Silhouette edges as welded vertex pairs (the input ids where no position repeats).
EdgeSet sideEdges(const EdgeTopology& topo, const PointSilhouette& s) {
  EdgeSet out;
  for (const auto& side : s.sides) {
    const EdgeTopology::Edge& e = topo.edges[side.edge];
    out.insert({e.v0, e.v1});
  }
  return out;
}

EdgeSet edgesOf(std::initializer_list<std::pair<std::uint32_t, std::uint32_t>> pairs) {
  EdgeSet out;
  for (auto [a, b] : pairs) out.insert(std::minmax(a, b));
  return out;
}

// Boundary of a 2-chain: at every vertex the signed multiplicities in and out balance, so the
// side quads close up into loops whatever the cap signs are (no cracks, hard case 9).
void expectClosedLoops(const EdgeTopology& topo, const PointSilhouette& s) {
  std::vector<int> balance(topo.weldedPositions.size(), 0);
  for (const auto& side : s.sides) {
    balance[topo.edges[side.edge].v0] += side.multiplicity;
    balance[topo.edges[side.edge].v1] -= side.multiplicity;
  }
  for (int b : balance) EXPECT_EQ(b, 0);
}

// The silhouette of a convex closed mesh, followed in the direction given by the signs, goes
// counter-clockwise around `inside` as seen from the light.
void expectCounterClockwise(const EdgeTopology& topo, const PointSilhouette& s, glm::dvec3 light, glm::dvec3 inside) {
  for (const auto& side : s.sides) {
    const EdgeTopology::Edge& e = topo.edges[side.edge];
    glm::dvec3 a(topo.weldedPositions[e.v0]), b(topo.weldedPositions[e.v1]);
    if (side.multiplicity < 0) std::swap(a, b);
    EXPECT_GT(glm::dot(glm::cross(b - a, inside - a), light - a), 0.0);
  }
}

TEST(GeometryTopology, CubeIsClosedWithDiagonals) {
  TriangleMesh m = cube();
  MeshReport r;
  cleanMesh(m, r);
  EXPECT_EQ(r.triangles, 12u);
  EXPECT_EQ(r.droppedTotal(), 0u);
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.openEdges + r.nonManifoldEdges + r.inconsistentEdges, 0u);
  EXPECT_EQ(r.components, 1u);
  const EdgeTopology topo = buildEdgeTopology(m);
  EXPECT_TRUE(topo.closed);
  EXPECT_EQ(topo.edges.size(), 18u);
  EXPECT_EQ(topo.weldedPositions.size(), 8u);
  EXPECT_EQ(volumeRuleFor(topo), VolumeRule::ClosedFrontFaces);
  for (std::size_t i = 0; i < topo.edges.size(); ++i) {
    EXPECT_LT(topo.edges[i].v0, topo.edges[i].v1);
    EXPECT_EQ(topo.edges[i].incidenceCount, 2u);
    if (i > 0) {
      EXPECT_LT(std::pair(topo.edges[i - 1].v0, topo.edges[i - 1].v1), std::pair(topo.edges[i].v0, topo.edges[i].v1));
    }
  }
  EXPECT_NE(r.summary().find("12 triangles, 0 dropped"), std::string::npos) << r.summary();
}

TEST(GeometryTopology, WeldsSplitVerticesAndNegativeZero) {
  TriangleMesh m = openQuad();
  m.positions.push_back({-0.0f, 0.0f, 0.0f});  // same point as vertex 0
  m.positions.push_back({1, 0, 1});            // same point as vertex 2
  m.triangles[1] = {4, 5, 3};
  const EdgeTopology topo = buildEdgeTopology(m);
  EXPECT_EQ(topo.weldedPositions.size(), 4u);
  EXPECT_EQ(topo.weldedIndex[4], topo.weldedIndex[0]);
  EXPECT_EQ(topo.weldedIndex[5], topo.weldedIndex[2]);
  EXPECT_EQ(topo.edges.size(), 5u);  // the diagonal is shared
}

TEST(GeometryTopology, CleanMeshCountsEachProblemOnce) {
  TriangleMesh m;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  m.positions = {{0, 0, 0},   {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {nan, 0, 0}, {0.5f, 0, 0},  // on the segment 0-1
                 {0, 0, 0},                                                                // a second copy of vertex 0
                 {0, 2e6f, 1}};
  m.triangles = {{0, 1, 2},   // kept
                 {0, 1, 99},  // invalid index
                 {0, 0, 1},   // repeated index
                 {0, 1, 5},   // zero area
                 {0, 1, 4},   // NaN vertex
                 {1, 2, 0},   // duplicate (rotated)
                 {2, 1, 0},   // duplicate (reversed winding)
                 {6, 1, 2},   // duplicate through the welded copy
                 {1, 3, 2},   // kept
                 {0, 7, 1}};  // kept, huge coordinate
  MeshReport r;
  cleanMesh(m, r);
  EXPECT_EQ(r.inputFaces, 10u);
  EXPECT_EQ(r.inputVertices, 8u);
  EXPECT_EQ(r.droppedInvalidIndex, 1u);
  EXPECT_EQ(r.droppedDegenerate, 2u);
  EXPECT_EQ(r.droppedNonFinite, 1u);
  EXPECT_EQ(r.droppedDuplicate, 3u);
  EXPECT_EQ(r.droppedTotal(), 7u);
  EXPECT_EQ(r.hugeCoordinates, 1u);
  ASSERT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(r.triangles, 3u);
  EXPECT_EQ(m.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(m.triangles[1], glm::uvec3(1, 3, 2));
  EXPECT_EQ(m.positions.size(), 8u);  // vertex arrays are kept
  const std::string s = r.summary();
  EXPECT_NE(s.find("3 triangles, 7 dropped"), std::string::npos) << s;
  EXPECT_NE(s.find("3 duplicate"), std::string::npos) << s;
}

TEST(GeometrySilhouette, CubeFromAbove) {
  TriangleMesh m = cube();
  const EdgeTopology topo = buildEdgeTopology(m);
  const glm::dvec3 light(0, 10, 0);
  const PointSilhouette s = extractPointSilhouette(topo, light, VolumeRule::ClosedFrontFaces);
  EXPECT_EQ(sideEdges(topo, s), edgesOf({{3, 7}, {7, 6}, {6, 2}, {2, 3}}));
  for (const auto& side : s.sides) EXPECT_EQ(std::abs(side.multiplicity), 1);
  const std::vector<std::int8_t> caps = {0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0};
  EXPECT_EQ(s.capSign, caps);
  expectCounterClockwise(topo, s, light, {0, 0, 0});
  expectClosedLoops(topo, s);
}

TEST(GeometrySilhouette, CubeFromBelowTheBottomFace) {
  const EdgeTopology topo = buildEdgeTopology(cube());
  const glm::dvec3 light(0.1, -0.2, -7);
  const PointSilhouette s = extractPointSilhouette(topo, light, VolumeRule::ClosedFrontFaces);
  EXPECT_EQ(sideEdges(topo, s), edgesOf({{0, 3}, {3, 2}, {2, 1}, {1, 0}}));
  expectCounterClockwise(topo, s, light, {0, 0, 0});
}

TEST(GeometrySilhouette, CubeFromTwoFaces) {
  const EdgeTopology topo = buildEdgeTopology(cube());
  const glm::dvec3 light(10, 10, 0);  // +x and +y face the light; their shared edge cancels
  const PointSilhouette s = extractPointSilhouette(topo, light, VolumeRule::ClosedFrontFaces);
  EXPECT_EQ(sideEdges(topo, s), edgesOf({{1, 2}, {2, 3}, {3, 7}, {7, 6}, {6, 5}, {5, 1}}));
  for (const auto& side : s.sides) EXPECT_EQ(std::abs(side.multiplicity), 1);
  expectCounterClockwise(topo, s, light, {0, 0, 0});
  expectClosedLoops(topo, s);
}

TEST(GeometrySilhouette, CubeFromTheDiagonalIsAHexagon) {
  const EdgeTopology topo = buildEdgeTopology(cube());
  const glm::dvec3 light(10, 10, 10);  // +x, +y, +z face the light; edges at corner 6 cancel
  const PointSilhouette s = extractPointSilhouette(topo, light, VolumeRule::ClosedFrontFaces);
  EXPECT_EQ(sideEdges(topo, s), edgesOf({{1, 2}, {2, 3}, {3, 7}, {7, 4}, {4, 5}, {5, 1}}));
  for (const auto& side : s.sides) EXPECT_EQ(std::abs(side.multiplicity), 1);
  int front = 0;
  for (std::int8_t c : s.capSign) front += c;
  EXPECT_EQ(front, 6);
  expectCounterClockwise(topo, s, light, {0, 0, 0});
  expectClosedLoops(topo, s);
}

TEST(GeometrySilhouette, LightInsideClosedMeshHasNoSides) {
  const EdgeTopology topo = buildEdgeTopology(cube());
  const PointSilhouette s = extractPointSilhouette(topo, {0.1, 0.2, -0.1}, VolumeRule::ClosedFrontFaces);
  EXPECT_TRUE(s.sides.empty());
}

// Hard case 27: where a point lies against the cube. Inside: winding 1; outside: 0 (also 1e-4
// beyond a vertex); exactly on a face, an edge or a vertex: on the surface; the inverted cube
// winds -1 inside.
TEST(GeometryInside, PointLocationOnTheCube) {
  const EdgeTopology topo = buildEdgeTopology(cube());
  EXPECT_EQ(locatePoint(topo, {0.1, 0.2, -0.1}).winding, 1);
  EXPECT_FALSE(locatePoint(topo, {0.1, 0.2, -0.1}).onSurface);
  EXPECT_EQ(locatePoint(topo, {0.49999, -0.49999, 0.49999}).winding, 1);
  EXPECT_EQ(locatePoint(topo, {0.5001, 0.5001, 0.5001}).winding, 0);
  EXPECT_EQ(locatePoint(topo, {0.3, 0.7, 0.0}).winding, 0);  // inside the box, above the cube
  EXPECT_EQ(locatePoint(topo, {3.0, 0.0, 0.0}).winding, 0);  // outside the bounding box
  for (glm::dvec3 on : {glm::dvec3(0.5, 0.1, 0.2), glm::dvec3(0.5, 0.5, 0.2), glm::dvec3(0.5, 0.5, 0.5),
                        glm::dvec3(0.0, 0.0, -0.5) /* on the -z face's diagonal */}) {
    const PointLocation at = locatePoint(topo, on);
    EXPECT_TRUE(at.onSurface) << on.x << " " << on.y << " " << on.z;
  }
  TriangleMesh inverted = cube();
  for (auto& t : inverted.triangles) std::swap(t.y, t.z);
  EXPECT_EQ(locatePoint(buildEdgeTopology(inverted), {0.1, 0.2, -0.1}).winding, -1);
}

// Hard case 28: a path from a centre outside to a sample inside enters through one triangle
// (side +1 -> -1), also when it passes exactly through a face's diagonal (the shared-edge
// tie-break claims it for one of the two triangles); a path ending on a face has side 0 there;
// a path beside the cube crosses nothing.
TEST(GeometryInside, PathCrossingsCountEachFaceOnce) {
  const EdgeTopology topo = buildEdgeTopology(cube());
  const glm::dvec3 c(0.9, 0.1, 0.2);
  std::vector<std::uint32_t> near = trianglesNearBall(topo, c, 1.0);
  ASSERT_FALSE(near.empty());
  auto crossings = [&](const glm::dvec3& from, const glm::dvec3& to) {
    std::vector<PathCrossing> out;
    pathCrossings(topo, trianglesNearBall(topo, from, glm::length(to - from)), from, to, out);
    return out;
  };
  std::vector<PathCrossing> in = crossings(c, {0.2, 0.1, 0.2});
  ASSERT_EQ(in.size(), 1u);
  EXPECT_EQ(in[0].sideC, 1);
  EXPECT_EQ(in[0].sideS, -1);
  // Through the +x face's diagonal (1,2,6)/(1,6,5) runs from (0.5,-0.5,-0.5) to (0.5,0.5,0.5).
  EXPECT_EQ(crossings({0.9, 0.1, 0.1}, {0.2, 0.1, 0.1}).size(), 1u);
  EXPECT_EQ(crossings({0.9, -0.2, -0.2}, {0.1, -0.2, -0.2}).size(), 1u);
  std::vector<PathCrossing> onFace = crossings(c, {0.5, 0.1, 0.2});
  ASSERT_EQ(onFace.size(), 1u);
  EXPECT_EQ(onFace[0].sideS, 0);
  EXPECT_TRUE(crossings(c, {0.9, 0.9, 0.2}).empty());
  // Through the cube: in and out.
  EXPECT_EQ(crossings({0.9, 0.1, 0.2}, {-0.9, 0.1, 0.2}).size(), 2u);
}

// Hard case 33: a path in a face's plane meets a segment of that plane (the border test dcs
// refuses a light by): crossing, touching at an end, running along it; not beside or short of it.
// findEdge finds an edge by its end points in either order.
TEST(GeometryInside, PathsInAFacesPlaneMeetItsEdges) {
  const EdgeTopology topo = buildEdgeTopology(cube());
  std::uint32_t t = 0;
  while (t < topo.weldedTriangles.size() && !(topo.weldedPositions[topo.weldedTriangles[t].x].x == 0.5f &&
                                              topo.weldedPositions[topo.weldedTriangles[t].y].x == 0.5f &&
                                              topo.weldedPositions[topo.weldedTriangles[t].z].x == 0.5f))
    ++t;
  ASSERT_LT(t, topo.weldedTriangles.size()) << "a triangle of the +x face";
  auto vertex = [&](const glm::vec3& p) {
    return std::uint32_t(std::find(topo.weldedPositions.begin(), topo.weldedPositions.end(), p) -
                         topo.weldedPositions.begin());
  };
  const std::uint32_t a = vertex({0.5f, 0.5f, -0.5f}), b = vertex({0.5f, 0.5f, 0.5f});
  EXPECT_LT(findEdge(topo, a, b), topo.edges.size());
  EXPECT_EQ(findEdge(topo, a, b), findEdge(topo, b, a));
  EXPECT_EQ(findEdge(topo, a, a), topo.edges.size());
  const glm::dvec3 u(0.5, 0.5, -0.5), v(0.5, 0.5, 0.5);
  EXPECT_TRUE(pathMeetsSegment(topo, t, u, v, {0.5, 0.0, 0.0}, {0.5, 0.8, 0.0}));   // across it
  EXPECT_TRUE(pathMeetsSegment(topo, t, u, v, {0.5, 0.0, 0.0}, {0.5, 0.5, 0.0}));   // ending on it
  EXPECT_TRUE(pathMeetsSegment(topo, t, u, v, {0.5, 0.5, -0.2}, {0.5, 0.5, 0.9}));  // along it
  EXPECT_FALSE(pathMeetsSegment(topo, t, u, v, {0.5, 0.0, 0.0}, {0.5, 0.3, 0.1}));  // short of it
  EXPECT_FALSE(pathMeetsSegment(topo, t, u, v, {0.5, 0.5, 0.6}, {0.5, 0.5, 0.9}));  // its line, beyond it
  EXPECT_FALSE(pathMeetsSegment(topo, t, u, v, {0.5, 0.0, 0.7}, {0.5, 0.8, 0.7}));  // beside it
}

// Hard case 4: the boundary of an open quad is a silhouette from both sides, with opposite
// signs; the shared diagonal cancels.
TEST(GeometrySilhouette, OpenQuadPerTriangle) {
  TriangleMesh m = openQuad();
  MeshReport r;
  cleanMesh(m, r);
  EXPECT_EQ(r.openEdges, 4u);
  EXPECT_FALSE(r.closed);
  const EdgeTopology topo = buildEdgeTopology(m);
  EXPECT_EQ(volumeRuleFor(topo), VolumeRule::PerTriangle);
  const EdgeSet boundary = edgesOf({{0, 1}, {1, 2}, {2, 3}, {3, 0}});
  const PointSilhouette above = extractPointSilhouette(topo, {0.3, 2, 0.6}, VolumeRule::PerTriangle);
  const PointSilhouette below = extractPointSilhouette(topo, {0.3, -2, 0.6}, VolumeRule::PerTriangle);
  EXPECT_EQ(sideEdges(topo, above), boundary);
  EXPECT_EQ(sideEdges(topo, below), boundary);
  EXPECT_EQ(above.capSign, std::vector<std::int8_t>({1, 1}));
  EXPECT_EQ(below.capSign, std::vector<std::int8_t>({-1, -1}));
  ASSERT_EQ(above.sides.size(), below.sides.size());
  for (std::size_t i = 0; i < above.sides.size(); ++i) {
    EXPECT_EQ(std::abs(above.sides[i].multiplicity), 1);
    EXPECT_EQ(above.sides[i].multiplicity, -below.sides[i].multiplicity);
  }
  expectClosedLoops(topo, above);
}

// Hard case 6: the spine of the book is shared by three triangles and carries the sum.
TEST(GeometrySilhouette, NonManifoldBook) {
  TriangleMesh m = book();
  MeshReport r;
  cleanMesh(m, r);
  EXPECT_EQ(r.nonManifoldEdges, 1u);
  EXPECT_EQ(r.openEdges, 9u);
  EXPECT_EQ(r.components, 1u);
  const EdgeTopology topo = buildEdgeTopology(m);
  EXPECT_EQ(topo.edges.size(), 13u);
  const auto spine =
      std::find_if(topo.edges.begin(), topo.edges.end(), [](const auto& e) { return e.incidenceCount == 3; });
  ASSERT_NE(spine, topo.edges.end());
  EXPECT_EQ(std::pair(spine->v0, spine->v1), std::pair(0u, 1u));
  // Spine triangles 1, 3, 4 traverse it 1->0, 1->0, 0->1 and face the light (0.3, 0.5, 2)
  // with normals +z, -x, +z: m = (+1)(-1) + (-1)(-1) + (+1)(+1) = 1.
  const PointSilhouette s = extractPointSilhouette(topo, {0.3, 0.5, 2}, VolumeRule::PerTriangle);
  const std::uint32_t spineIndex = static_cast<std::uint32_t>(spine - topo.edges.begin());
  const auto side = std::find_if(s.sides.begin(), s.sides.end(), [&](const auto& sd) { return sd.edge == spineIndex; });
  ASSERT_NE(side, s.sides.end());
  EXPECT_EQ(side->multiplicity, 1);
  int sum = 0;
  for (std::uint32_t k = 0; k < spine->incidenceCount; ++k) {
    const auto& inc = topo.incidences[spine->firstIncidence + k];
    sum += s.capSign[inc.triangle] * inc.orientation;
  }
  EXPECT_EQ(sum, 1);
  expectClosedLoops(topo, s);
}

// Hard case 7: one flipped triangle. The per-triangle rule does not depend on winding, so the
// silhouette is the same as for the intact cube.
TEST(GeometrySilhouette, FlippedTriangle) {
  TriangleMesh flipped = cube();
  std::swap(flipped.triangles[0].y, flipped.triangles[0].z);
  MeshReport r;
  cleanMesh(flipped, r);
  EXPECT_EQ(r.inconsistentEdges, 3u);
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.openEdges, 0u);
  const EdgeTopology a = buildEdgeTopology(cube()), b = buildEdgeTopology(flipped);
  EXPECT_EQ(volumeRuleFor(b), VolumeRule::PerTriangle);
  for (const glm::dvec3 light :
       {glm::dvec3(0, 10, 0), glm::dvec3(10, 10, 10), glm::dvec3(0.2, -0.3, -4), glm::dvec3(0.1, 0.1, 0.1)}) {
    const PointSilhouette sa = extractPointSilhouette(a, light, VolumeRule::PerTriangle);
    const PointSilhouette sb = extractPointSilhouette(b, light, VolumeRule::PerTriangle);
    ASSERT_EQ(sa.sides.size(), sb.sides.size());
    for (std::size_t i = 0; i < sa.sides.size(); ++i) {
      EXPECT_EQ(sa.sides[i].edge, sb.sides[i].edge);
      EXPECT_EQ(sa.sides[i].multiplicity, sb.sides[i].multiplicity);
    }
    EXPECT_EQ(sa.capSign[0], -sb.capSign[0]);
  }
}

// Hard case 9: light in the plane of the top face; the face gets c = 0 under both rules.
TEST(GeometrySilhouette, LightInThePlaneOfAFace) {
  const EdgeTopology topo = buildEdgeTopology(cube());
  const glm::dvec3 light(2, 0.5, 0.3);
  for (VolumeRule rule : {VolumeRule::ClosedFrontFaces, VolumeRule::PerTriangle}) {
    const PointSilhouette s = extractPointSilhouette(topo, light, rule);
    EXPECT_EQ(s.capSign[6], 0);
    EXPECT_EQ(s.capSign[7], 0);
    expectClosedLoops(topo, s);
    const PointSilhouette again = extractPointSilhouette(topo, light, rule);
    EXPECT_EQ(again.capSign, s.capSign);
    ASSERT_EQ(again.sides.size(), s.sides.size());
    for (std::size_t i = 0; i < s.sides.size(); ++i) {
      EXPECT_EQ(again.sides[i].edge, s.sides[i].edge);
      EXPECT_EQ(again.sides[i].multiplicity, s.sides[i].multiplicity);
    }
  }
  // Only +x faces the light: its rim is the silhouette.
  const PointSilhouette s = extractPointSilhouette(topo, light, VolumeRule::ClosedFrontFaces);
  EXPECT_EQ(sideEdges(topo, s), edgesOf({{1, 2}, {2, 6}, {6, 5}, {5, 1}}));
  // Light on a vertex and light on a ground plane: every incident face is edge-on.
  const PointSilhouette corner = extractPointSilhouette(topo, {0.5, 0.5, 0.5}, VolumeRule::PerTriangle);
  expectClosedLoops(topo, corner);
  const EdgeTopology ground = buildEdgeTopology(openQuad());
  const PointSilhouette onPlane = extractPointSilhouette(ground, {5, 0, -3}, VolumeRule::PerTriangle);
  EXPECT_TRUE(onPlane.sides.empty());
  EXPECT_EQ(onPlane.capSign, std::vector<std::int8_t>({0, 0}));
}

TEST(GeometrySilhouette, MatchesBruteForceOnRandomClosedMesh) {
  std::mt19937 rng(1234);
  TriangleMesh m = bumpySphere(2, rng);
  MeshReport r;
  cleanMesh(m, r);
  ASSERT_EQ(r.triangles, 320u);
  ASSERT_TRUE(r.closed);
  const EdgeTopology topo = buildEdgeTopology(m);
  std::uniform_real_distribution<double> coord(-3.0, 3.0);
  const auto& p = topo.weldedPositions;
  for (int trial = 0; trial < 40; ++trial) {
    const glm::dvec3 l(coord(rng), coord(rng), coord(rng));
    for (VolumeRule rule : {VolumeRule::ClosedFrontFaces, VolumeRule::PerTriangle}) {
      const PointSilhouette s = extractPointSilhouette(topo, l, rule);
      std::map<std::pair<std::uint32_t, std::uint32_t>, int> fast;
      for (const auto& side : s.sides) fast[{topo.edges[side.edge].v0, topo.edges[side.edge].v1}] = side.multiplicity;
      // O(E * T): every edge against every triangle, facing recomputed from scratch.
      std::map<std::pair<std::uint32_t, std::uint32_t>, int> slow;
      for (const auto& e : topo.edges) {
        int mult = 0;
        for (const glm::uvec3& t : topo.weldedTriangles) {
          for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = t[k], b = t[(k + 1) % 3];
            if (std::min(a, b) != e.v0 || std::max(a, b) != e.v1) continue;
            const glm::dvec3 p0(p[t.x]), u = glm::dvec3(p[t.y]) - p0, v = glm::dvec3(p[t.z]) - p0;
            const glm::dvec3 n(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
            const double d = n.x * (l.x - p0.x) + n.y * (l.y - p0.y) + n.z * (l.z - p0.z);
            const int facing = d > 0 ? 1 : d < 0 ? -1 : 0;
            const int c = rule == VolumeRule::PerTriangle ? facing : facing > 0;
            mult += c * (a < b ? 1 : -1);
          }
        }
        if (mult != 0) slow[{e.v0, e.v1}] = mult;
      }
      EXPECT_EQ(fast, slow) << "light " << l.x << " " << l.y << " " << l.z;
      expectClosedLoops(topo, s);
      if (rule == VolumeRule::ClosedFrontFaces) {
        for (const auto& side : s.sides) EXPECT_EQ(std::abs(side.multiplicity), 1);
      }
    }
  }
}

TEST(GeometrySilhouette, FastOnLargeMeshes) {
  std::mt19937 rng(7);
  TriangleMesh m = bumpySphere(6, rng);  // 81920 triangles
  MeshReport r;
  cleanMesh(m, r);
  ASSERT_TRUE(r.closed);
  const EdgeTopology topo = buildEdgeTopology(m);
  const auto start = std::chrono::steady_clock::now();
  std::size_t sides = 0;
  for (int i = 0; i < 10; ++i)
    sides += extractPointSilhouette(topo, {3.0 + i, 2, 1}, VolumeRule::ClosedFrontFaces).sides.size();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GT(sides, 0u);
  // A gate against a quadratic extraction (hundreds of times slower here), not a benchmark.
  // Twenty runs each (tests/spread.sh, 2026-12-06, 2 cores, other tests running beside them):
  // 1.07-3.51 ms a silhouette (median 1.66); under ASan + UBSan 9.8-23.0 ms (median 15.0) with
  // three GL tests beside it. The bound, 100 ms, is 4.3 times the slowest of those 40 runs.
  EXPECT_LT(ms / 10, 100.0) << ms / 10 << " ms per silhouette";
  RecordProperty("ms_per_silhouette_81920_triangles", std::to_string(ms / 10));
}

}  // namespace
}  // namespace penumbra::geo
