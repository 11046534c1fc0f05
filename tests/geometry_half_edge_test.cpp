// The OpenMesh half-edge mesh behind EdgeTopology: refused faces copied and counted, edges and
// face normals equal to a brute-force count on random soups, and the crease-angle corner normals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "geometry/half_edge_mesh.h"
#include "geometry/mesh.h"
#include "geometry_test_meshes.h"

namespace penumbra::geo {
namespace {

using test::book;
using test::cube;

constexpr double kPi = 3.14159265358979323846;

// The same cube with its own three vertices per triangle (split normals or UVs in a file).
TriangleMesh splitCube() {
  const TriangleMesh c = cube();
  TriangleMesh m;
  for (const glm::uvec3& t : c.triangles) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (int k = 0; k < 3; ++k) m.positions.push_back(c.positions[t[k]]);
    m.triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

glm::dvec3 unitNormal(const EdgeTopology& topo, std::size_t t) { return glm::normalize(topo.faceNormals[t]); }

void expectNear(const glm::vec3& a, const glm::dvec3& b, double tol, const char* what) {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

TEST(GeometryHalfEdge, CubeIsOneManifoldOpenMeshWithoutCopies) {
  const EdgeTopology topo = buildEdgeTopology(cube());
  ASSERT_NE(topo.halfEdges, nullptr);
  const SilhouetteTriMesh& m = topo.halfEdges->mesh;
  EXPECT_EQ(m.n_vertices(), 8u);
  EXPECT_EQ(m.n_faces(), 12u);
  EXPECT_EQ(m.n_edges(), 18u);
  EXPECT_EQ(topo.duplicatedVertices, 0u);
  EXPECT_TRUE(topo.halfEdges->refused.empty());
  for (const auto e : m.edges()) EXPECT_FALSE(m.is_boundary(e));
  for (const auto v : m.vertices()) EXPECT_TRUE(m.is_manifold(v));
  // Each topology edge is one OpenMesh edge: the same count, and each has both faces.
  ASSERT_EQ(topo.edges.size(), m.n_edges());
  EXPECT_TRUE(topo.closed);
}

// add_face refuses the book's third page on the spine (the spine's halfedges both have a face
// already): its three vertices are copied, and welding still sums the spine over 3 triangles.
TEST(GeometryHalfEdge, BookCopiesTheRefusedPageAndCountsIt) {
  TriangleMesh m = book();
  MeshReport r;
  cleanMesh(m, r);
  const EdgeTopology topo = buildEdgeTopology(m);
  EXPECT_EQ(topo.halfEdges->refused, std::vector<std::uint32_t>({3}));
  EXPECT_EQ(topo.duplicatedVertices, 3u);
  EXPECT_EQ(topo.halfEdges->mesh.n_vertices(), topo.weldedPositions.size() + 3);
  EXPECT_EQ(r.duplicatedVertices, 3u);
  EXPECT_EQ(r.nonManifoldEdges, 1u);
  EXPECT_NE(r.summary().find("3 vertices duplicated for refused faces"), std::string::npos) << r.summary();
  // The copies are the refused triangle's welded vertices, in its order.
  const HalfEdgeMesh& hem = *topo.halfEdges;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(hem.weldedOf[hem.weldedCount + std::size_t(k)], topo.weldedTriangles[3][k]);
}

// A flipped triangle runs its three edges the same way as its neighbours: complex edges. The
// first face added wins, so the flipped face 0 stays and its three neighbours are copied.
TEST(GeometryHalfEdge, InconsistentWindingIsCopied) {
  TriangleMesh flipped = cube();
  std::swap(flipped.triangles[0].y, flipped.triangles[0].z);
  const EdgeTopology topo = buildEdgeTopology(flipped);
  EXPECT_EQ(topo.halfEdges->refused, std::vector<std::uint32_t>({1, 7, 9}));
  EXPECT_EQ(topo.duplicatedVertices, 9u);
  // Welding joins the copies again: the same 18 edges, 2 incidences each, 3 of them inconsistent.
  ASSERT_EQ(topo.edges.size(), 18u);
  for (const EdgeTopology::Edge& e : topo.edges) EXPECT_EQ(e.incidenceCount, 2u);
  EXPECT_FALSE(topo.closed);
}

// Two cubes touching at one corner: add_face refuses the second cube's faces at the shared,
// already interior vertex (complex vertex). Their copies weld back, so every edge still has two
// opposite incidences and the union stays closed (ClosedFrontFaces applies).
TEST(GeometryHalfEdge, CubesTouchingAtACornerStayClosed) {
  TriangleMesh m = cube();
  const TriangleMesh other = cube();
  for (const glm::vec3& p : other.positions) m.positions.push_back(p + glm::vec3(1.0f));
  for (const glm::uvec3& t : other.triangles) m.triangles.push_back(t + glm::uvec3(8));
  MeshReport r;
  cleanMesh(m, r);
  EXPECT_GT(r.duplicatedVertices, 0u);
  EXPECT_EQ(r.duplicatedVertices % 3, 0u);
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.nonManifoldEdges, 0u);
  EXPECT_EQ(r.openEdges, 0u);
  EXPECT_EQ(r.components, 2u);
  const EdgeTopology topo = buildEdgeTopology(m);
  EXPECT_EQ(topo.edges.size(), 36u);
  EXPECT_TRUE(topo.closed);
}

// Random soups over a small grid, with repeated positions (welded), repeated and reversed
// triangles, collinear ones and triangles that collapse under welding: the edges, their
// incidences and the face normals equal a brute-force count over the triangles.
TEST(GeometryHalfEdge, MatchesBruteForceOnRandomSoups) {
  std::mt19937 rng(99);
  for (int trial = 0; trial < 60; ++trial) {
    TriangleMesh m;
    std::uniform_int_distribution<int> grid(0, 2);
    const int points = 6 + trial % 10;
    for (int i = 0; i < points; ++i) m.positions.push_back(glm::vec3(grid(rng), grid(rng), 0.5f * float(grid(rng))));
    std::uniform_int_distribution<std::uint32_t> vertex(0, std::uint32_t(points - 1));
    const int triangles = 4 + trial;
    for (int i = 0; i < triangles; ++i) {
      glm::uvec3 t(vertex(rng), vertex(rng), vertex(rng));
      if (t.x == t.y || t.y == t.z || t.z == t.x) t = {0, 1, 2};
      m.triangles.push_back(t);
    }
    const EdgeTopology topo = buildEdgeTopology(m);
    const auto& P = topo.weldedPositions;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::uint32_t, int>>> expected;
    std::size_t kept = 0;
    for (std::uint32_t t = 0; t < topo.weldedTriangles.size(); ++t) {
      const glm::uvec3& w = topo.weldedTriangles[t];
      const glm::dvec3 p0(P[w.x]);
      const glm::dvec3 n = glm::cross(glm::dvec3(P[w.y]) - p0, glm::dvec3(P[w.z]) - p0);
      const bool collapsed = w.x == w.y || w.y == w.z || w.z == w.x;
      EXPECT_EQ(topo.faceNormals[t], collapsed ? glm::dvec3(0.0) : n) << "trial " << trial << " triangle " << t;
      if (collapsed) continue;
      ++kept;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = w[k], b = w[(k + 1) % 3];
        expected[{std::min(a, b), std::max(a, b)}].push_back({t, a < b ? 1 : -1});
      }
    }
    EXPECT_EQ(topo.halfEdges->mesh.n_faces(), kept);
    EXPECT_EQ(topo.duplicatedVertices, 3 * topo.halfEdges->refused.size());
    bool closed = !expected.empty();
    ASSERT_EQ(topo.edges.size(), expected.size()) << "trial " << trial;
    auto it = expected.begin();
    for (const EdgeTopology::Edge& e : topo.edges) {
      std::sort(it->second.begin(), it->second.end());
      EXPECT_EQ(std::pair(e.v0, e.v1), it->first);
      std::vector<std::pair<std::uint32_t, int>> got;
      for (std::uint32_t k = 0; k < e.incidenceCount; ++k) {
        const EdgeTopology::Incidence& inc = topo.incidences[e.firstIncidence + k];
        got.push_back({inc.triangle, inc.orientation});
      }
      EXPECT_EQ(got, it->second) << "trial " << trial << " edge " << e.v0 << "-" << e.v1;
      closed = closed && it->second.size() == 2 && it->second[0].second + it->second[1].second == 0;
      ++it;
    }
    EXPECT_EQ(topo.closed, closed) << "trial " << trial;
  }
}

// Below the crease angle every corner is flat; at pi the cube's corners point along the
// diagonals, because each face meets a corner at 90 degrees in total however it is triangulated
// (angle weighting, not triangle counting: a corner is in one or two triangles of a face).
TEST(GeometryHalfEdge, CornerNormalsOfTheCube) {
  for (const TriangleMesh& m : {cube(), splitCube()}) {
    const EdgeTopology topo = buildEdgeTopology(m);
    const std::vector<glm::vec3> flat = cornerNormals(topo, 0.5);
    const std::vector<glm::vec3> smooth = cornerNormals(topo, kPi);
    ASSERT_EQ(flat.size(), 3 * m.triangles.size());
    ASSERT_EQ(smooth.size(), 3 * m.triangles.size());
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      for (int c = 0; c < 3; ++c) {
        expectNear(flat[3 * t + std::size_t(c)], unitNormal(topo, t), 1e-7, "flat");
        const glm::dvec3 corner(m.positions[m.triangles[t][c]]);
        expectNear(smooth[3 * t + std::size_t(c)], glm::normalize(corner), 1e-6, "smooth");
      }
    }
  }
}

// Splitting the +z face into four triangles around its centre changes nothing at the cube's
// corners (each still sees 90 degrees of that face); the centre is flat.
TEST(GeometryHalfEdge, CornerNormalsAreAngleWeighted) {
  TriangleMesh m = cube();
  m.positions.push_back({0.0f, 0.0f, 0.5f});  // 8: centre of +z
  m.triangles[2] = {4, 5, 8};
  m.triangles[3] = {5, 6, 8};
  m.triangles.push_back({6, 7, 8});
  m.triangles.push_back({7, 4, 8});
  const EdgeTopology topo = buildEdgeTopology(m);
  ASSERT_TRUE(topo.closed);
  const std::vector<glm::vec3> n = cornerNormals(topo, kPi);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3 p(m.positions[m.triangles[t][c]]);
      expectNear(n[3 * t + std::size_t(c)], p.x == 0.0 ? glm::dvec3(0, 0, 1) : glm::normalize(p), 1e-6, "split face");
    }
  }
}

// A roof of two quads whose normals are 60 degrees apart: a crease below 60 degrees keeps both
// flat; above it the ridge's corners take the bisector (equal angles on both sides).
TEST(GeometryHalfEdge, CreaseAngleDecidesTheRidge) {
  const float s = std::sqrt(3.0f);
  TriangleMesh m;
  // Ridge along z at (0, 1); the slopes fall to x = -s and x = +s at y = 0: normals
  // (-1, s, 0)/2 and (1, s, 0)/2, 60 degrees apart.
  m.positions = {{0, 1, 0}, {0, 1, 1}, {-s, 0, 0}, {-s, 0, 1}, {s, 0, 0}, {s, 0, 1}};
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {0, 1, 5}, {0, 5, 4}};
  const EdgeTopology topo = buildEdgeTopology(m);
  const std::vector<glm::vec3> sharp = cornerNormals(topo, 55.0 * kPi / 180.0);
  const std::vector<glm::vec3> soft = cornerNormals(topo, 65.0 * kPi / 180.0);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const std::size_t i = 3 * t + std::size_t(c);
      const bool ridge = m.positions[m.triangles[t][c]].y == 1.0f;
      expectNear(sharp[i], unitNormal(topo, t), 1e-6, "below the crease angle");
      expectNear(soft[i], ridge ? glm::dvec3(0, 1, 0) : unitNormal(topo, t), 1e-6, "above the crease angle");
    }
  }
}

// The refused page's copied vertices join no other face: its corners stay flat even at pi,
// while page 1 and the third page, joined on the spine, smooth across it.
TEST(GeometryHalfEdge, RefusedFacesKeepTheirFaceNormal) {
  const TriangleMesh m = book();
  const EdgeTopology topo = buildEdgeTopology(m);
  const std::vector<glm::vec3> n = cornerNormals(topo, kPi);
  for (int c = 0; c < 3; ++c) expectNear(n[3 * 3 + std::size_t(c)], unitNormal(topo, 3), 1e-7, "refused");
  // Triangle 1 (page 1, +z) and triangle 4 (page 3, +z) share the spine and one plane.
  for (int c = 0; c < 3; ++c) expectNear(n[3 * 4 + std::size_t(c)], glm::dvec3(0, 0, 1), 1e-7, "page 3");
}

// On a smooth closed mesh every corner of a vertex gets the same normal, whichever corner the
// walk round the vertex starts from.
TEST(GeometryHalfEdge, SmoothCornersAgreeAtEachVertex) {
  TriangleMesh m;
  const int segments = 24, rings = 12;
  for (int r = 0; r <= rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const double theta = kPi * r / rings, phi = 2 * kPi * s / segments;
      if (r == 0 || r == rings) {  // the poles exactly, so that each ring welds to one vertex
        m.positions.push_back(glm::vec3(0.0f, r == 0 ? 1.0f : -1.0f, 0.0f));
        continue;
      }
      m.positions.push_back(
          glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t a = std::uint32_t(r * segments + s), b = std::uint32_t(r * segments + (s + 1) % segments);
      const std::uint32_t c = a + std::uint32_t(segments), d = b + std::uint32_t(segments);
      if (r > 0) m.triangles.push_back({a, b, c});
      if (r < rings - 1) m.triangles.push_back({b, d, c});
    }
  }
  MeshReport report;
  cleanMesh(m, report);  // drops nothing: the pole rings weld to one vertex each
  ASSERT_TRUE(report.closed);
  const EdgeTopology topo = buildEdgeTopology(m);
  EXPECT_EQ(topo.duplicatedVertices, 0u);
  const std::vector<glm::vec3> n = cornerNormals(topo, 40.0 * kPi / 180.0);
  std::map<std::uint32_t, glm::vec3> first;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t w = topo.weldedTriangles[t][c];
      const glm::vec3 normal = n[3 * t + std::size_t(c)];
      EXPECT_NEAR(glm::length(normal), 1.0f, 1e-6f);
      EXPECT_GT(glm::dot(glm::dvec3(normal), glm::normalize(glm::dvec3(topo.weldedPositions[w]))), 0.99);
      const auto [it, added] = first.try_emplace(w, normal);
      if (!added) expectNear(normal, glm::dvec3(it->second), 1e-6, "same vertex");
    }
  }
}

}  // namespace
}  // namespace penumbra::geo
