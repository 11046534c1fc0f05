// The shadow-volume count's exact face decisions (shaders/volume_count.h, "Which faces of the shadow volumes
// the view ray meets", compiled here as C++) and the covers it draws them with
// (techniques/common/shadow_volume/volume_cover.h). No GL.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "geometry/mesh.h"
#include "geometry/silhouette.h"
#include "techniques/common/shadow_volume/volume_count.hpp"
#include "techniques/common/shadow_volume/volume_cover.h"

namespace penumbra {
namespace {

using shared::penumbraFarCapCount;
using shared::penumbraNearCapCount;
using shared::penumbraSideCount;

// The count at o seen from `eye` with the light at c, every face decided by shaders/volume_count.h, as the
// fragment shader sums it (hardsv_volume.frag, the faces as shadow_volume.cpp lists them).
float sharedCount(const geo::EdgeTopology& topo, geo::VolumeRule rule, glm::vec3 c, glm::vec3 o, glm::vec3 eye) {
  const glm::vec3 d = o - eye, n = glm::cross(d, o - c);
  const auto sil = geo::extractPointSilhouette(topo, glm::dvec3(c), rule);
  const auto& P = topo.weldedPositions;
  float count = 0.0f;
  for (const auto& s : sil.sides) {
    const auto& e = topo.edges[s.edge];
    count += penumbraSideCount(P[e.v0], P[e.v1], float(s.multiplicity), c, o, d, n);
  }
  for (std::size_t t = 0; t < sil.capSign.size(); ++t) {
    if (sil.capSign[t] == 0) continue;
    const glm::uvec3 tri = topo.weldedTriangles[t];
    const glm::uvec3 v = sil.capSign[t] > 0 ? tri : glm::uvec3(tri.x, tri.z, tri.y);
    count += penumbraNearCapCount(P[v.x], P[v.y], P[v.z], 1.0f, o, d);
    count += penumbraFarCapCount(P[v.x], P[v.y], P[v.z], 1.0f, c, d);
  }
  return count;
}

// A height field z = h(x, y) over [-1, 1]^2 on an n x n grid, bumpy, its vertices on a float
// grid of 1/64 so that lines through them are exactly representable as often as possible.
geo::TriangleMesh heightField(int n, std::mt19937& rng) {
  std::uniform_real_distribution<float> bump(-0.25f, 0.25f);
  geo::TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.positions.emplace_back(-1.0f + 2.0f * float(i) / float(n), -1.0f + 2.0f * float(j) / float(n),
                               std::round(bump(rng) * 64.0f) / 64.0f);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n + 1), d = c + 1;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  return m;
}

// Surfaces the segment o -> c crosses, in double (Möller-Trumbore); -1 when it passes within
// 1e-9 (barycentric) of a triangle's border, where a count is not defined to compare with.
int crossings(const geo::EdgeTopology& topo, glm::dvec3 o, glm::dvec3 c) {
  int n = 0;
  const glm::dvec3 d = c - o;
  for (const glm::uvec3& t : topo.weldedTriangles) {
    const glm::dvec3 a(topo.weldedPositions[t.x]), e1 = glm::dvec3(topo.weldedPositions[t.y]) - a,
                                                   e2 = glm::dvec3(topo.weldedPositions[t.z]) - a;
    const glm::dvec3 p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) continue;
    const glm::dvec3 s = o - a, q = glm::cross(s, e1);
    const double b1 = glm::dot(s, p) / det, b2 = glm::dot(d, q) / det, t01 = glm::dot(e2, q) / det;
    if (t01 <= 0.0 || t01 >= 1.0) continue;
    const double margin = std::min({b1, b2, 1.0 - b1 - b2});
    if (std::abs(margin) < 1e-9) return -1;
    n += margin > 0.0;
  }
  return n;
}

// o lies within 1e-5 (relative) of the plane of a side or a cap: there the side it is on is a
// float decision (shared with dcs's wedges, consistent, but not the double one).
bool nearAPlane(const geo::EdgeTopology& topo, const geo::PointSilhouette& sil, glm::dvec3 c, glm::dvec3 o) {
  const auto& P = topo.weldedPositions;
  for (const auto& s : sil.sides) {
    const glm::dvec3 n = glm::cross(glm::dvec3(P[topo.edges[s.edge].v0]) - c, glm::dvec3(P[topo.edges[s.edge].v1]) - c);
    if (std::abs(glm::dot(n, o - c)) < 1e-5 * glm::length(n) * glm::length(o - c)) return true;
  }
  for (std::size_t t = 0; t < sil.capSign.size(); ++t) {
    if (sil.capSign[t] == 0) continue;
    const glm::uvec3 tri = topo.weldedTriangles[t];
    const glm::dvec3 x(P[tri.x]);
    const glm::dvec3 n = glm::cross(glm::dvec3(P[tri.y]) - x, glm::dvec3(P[tri.z]) - x);
    if (std::abs(glm::dot(n, o - x)) < 1e-5 * glm::length(n) * glm::length(o - x)) return true;
  }
  return false;
}

// A sphere (closed: silhouette sides and front caps).
geo::TriangleMesh sphereMesh() {
  geo::TriangleMesh m;
  const int rings = 9, segments = 14;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const double th = M_PI * j / rings, ph = 2.0 * M_PI * i / segments;
      const double r = j == 0 || j == rings ? 0.0 : std::sin(th);  // the poles exactly
      m.positions.emplace_back(float(r * std::cos(ph)), float(r * std::sin(ph)),
                               float(j == 0       ? 1.0
                                     : j == rings ? -1.0
                                                  : std::cos(th)));
    }
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const std::uint32_t a = std::uint32_t(j * segments + i), b = std::uint32_t(j * segments + (i + 1) % segments);
      const std::uint32_t c = a + std::uint32_t(segments), d = b + std::uint32_t(segments);
      if (j > 0) m.triangles.push_back({a, c, b});
      if (j < rings - 1) m.triangles.push_back({b, c, d});
    }
  geo::MeshReport report;
  geo::cleanMesh(m, report);
  return m;
}

// Hard case 34: a view ray through the line from the light through a vertex where several
// volume faces meet. Evaluation points near the vertex lines of every silhouette vertex, beyond
// the vertex from the light, off the line by 1e-6 to 1e-3 of their magnitude (below a pixel:
// where the rasterised decision went wrong) and not within 1e-5 of a face's plane (where which
// side the point is on is a float decision), from many eyes: the count equals the surfaces the segment to the light
// crosses (a closed mesh: whether it passes through it), in double. A sphere lit from anywhere (closed: silhouette
// sides, front caps) and a height field lit from low on one side (one volume per triangle: the folds towards and away
// from the light are sides inside it).
TEST(VolumeCount, AViewRayNearAVertexLineCountsEveryVolumeOnce) {
  std::mt19937 rng(34);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const geo::EdgeTopology sphere = geo::buildEdgeTopology(sphereMesh());
  const geo::EdgeTopology field = geo::buildEdgeTopology(heightField(6, rng));
  ASSERT_TRUE(sphere.closed);
  int checked = 0, wrong = 0, onLine = 0, offOnLine = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const bool closed = trial % 2 == 0;
    const geo::EdgeTopology& topo = closed ? sphere : field;
    const geo::VolumeRule rule = closed ? geo::VolumeRule::ClosedFrontFaces : geo::VolumeRule::PerTriangle;
    const glm::dvec3 c = closed ? 4.0 * glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)))
                                : glm::dvec3(3.0 + u(rng), 0.5 * u(rng), 0.4 + 0.1 * u(rng));
    const glm::dvec3 eye = closed ? 6.0 * glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)))
                                  : glm::dvec3(2.0 * u(rng), 2.0 * u(rng), 2.0 + u(rng));
    const auto sil = geo::extractPointSilhouette(topo, c, rule);
    for (const auto& s : sil.sides)
      for (std::uint32_t id : {topo.edges[s.edge].v0, topo.edges[s.edge].v1}) {
        const glm::dvec3 v(topo.weldedPositions[id]);
        const glm::dvec3 across = glm::normalize(glm::cross(v - c, glm::dvec3(u(rng), u(rng), u(rng))));
        for (double t : {0.3, 1.5}) {
          const glm::dvec3 line = v + t * (v - c);
          for (double off : {0.0, 1e-6, 1e-5, 1e-4, 1e-3}) {
            const glm::vec3 o(line + off * glm::length(line) * across);
            const int expected = crossings(topo, glm::dvec3(o), c);
            if (expected < 0 || (off > 0.0 && nearAPlane(topo, sil, c, glm::dvec3(o)))) continue;
            const float truth = closed ? float(expected > 0) : float(expected);
            const float count = sharedCount(topo, rule, glm::vec3(c), o, glm::vec3(eye));
            if (off == 0.0) {
              ++onLine;
              offOnLine += count != truth;
            } else {
              ++checked;
              wrong += count != truth;
            }
          }
        }
      }
  }
  EXPECT_EQ(wrong, 0) << "of " << checked << " evaluation points near vertex lines";
  EXPECT_GT(checked, 5000);
  // On the line itself, within rounding of both side planes, the two sides' decisions are
  // rounding: measured, not gated.
  RecordProperty("on_the_line_counted_otherwise", std::to_string(offOnLine) + " of " + std::to_string(onLine));
  std::printf(
      "%d points near vertex lines, all counted as the double crossings; on a line (within rounding): %d of %d "
      "counted otherwise\n",
      checked, offOnLine, onLine);
}

// Away from any degeneracy the count is the number of volumes: closed objects or surfaces
// crossed by the segment to the light (a height field: 1 below, 0 above), from random points.
TEST(VolumeCount, CountsTheSurfacesBetweenAPointAndTheLight) {
  std::mt19937 rng(36);
  const geo::EdgeTopology topo = geo::buildEdgeTopology(heightField(5, rng));
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int trial = 0; trial < 300; ++trial) {
    const glm::vec3 c(0.3f * u(rng), 0.3f * u(rng), 3.0f);
    const glm::vec3 eye(3.0f * u(rng), 3.0f * u(rng), 1.5f + u(rng));
    const bool below = trial % 2 == 0;
    const glm::vec3 o(0.6f * u(rng), 0.6f * u(rng), below ? -0.6f : 0.6f);
    EXPECT_EQ(sharedCount(topo, geo::VolumeRule::PerTriangle, c, o, eye), below ? 1.0f : 0.0f) << trial;
  }
}

// A convex polygon (counter-clockwise) holds x with a margin m in the max norm.
bool holds(const std::vector<glm::vec2>& poly, glm::dvec2 x, double m) {
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec2 a(poly[i]), b(poly[(i + 1) % poly.size()]);
    const glm::dvec2 e = b - a, n(e.y, -e.x);  // outward for counter-clockwise
    const double len = glm::length(n);
    if (len == 0.0) continue;
    if (glm::dot(x - a, n) / len > -m * (std::abs(n.x) + std::abs(n.y)) / len + 1e-9) return false;
  }
  return true;
}

// Every point of a face that lies on screen (in front of the eye beyond clipNear) is inside its
// cover by the margin; the cover is convex. Faces as the count draws them: caps (finite
// triangles), far caps (triangles at infinity) and sides (two finite points, two at infinity),
// from random cameras, including faces that pass behind the eye.
TEST(VolumeCover, HoldsEveryPixelOfTheFaceWithItsMargin) {
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> u(-1.0, 1.0), t01(0.0, 1.0);
  CoverView view;
  view.viewport = {96.0, 64.0};
  view.clipNear = 0.025;
  view.margin = coverMargin(8);
  int points = 0, missed = 0, concave = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const glm::dvec3 eye(3.0 * u(rng), 3.0 * u(rng), 3.0 * u(rng));
    const glm::dmat4 viewMatrix =
        glm::lookAt(eye, glm::dvec3(0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)), glm::dvec3(0, 1, 0));
    view.clipFromWorld = glm::perspective(glm::radians(50.0), 1.5, 0.05, 100.0) * viewMatrix;
    view.light = glm::dvec3(2.0 * u(rng), 4.0, 2.0 * u(rng));
    const int kind = trial % 3;
    glm::dvec3 p[3];
    for (auto& x : p) x = glm::dvec3(2.0 * u(rng), 2.0 * u(rng), 2.0 * u(rng));
    glm::dvec4 corners[4];
    int n = 3;
    if (kind == 0) {
      for (int i = 0; i < 3; ++i) corners[i] = glm::dvec4(p[i], 1.0);
    } else if (kind == 1) {
      for (int i = 0; i < 3; ++i) corners[i] = glm::dvec4(p[i], 0.0);
    } else {
      n = 4;
      corners[0] = glm::dvec4(p[1], 1.0), corners[1] = glm::dvec4(p[0], 1.0);
      corners[2] = glm::dvec4(p[0], 0.0), corners[3] = glm::dvec4(p[1], 0.0);
    }
    std::vector<glm::vec2> cover;
    appendCover(view, corners, n, cover);
    for (std::size_t i = 0; i < cover.size() && cover.size() >= 3; ++i) {
      const glm::dvec2 a(cover[i]), b(cover[(i + 1) % cover.size()]), c(cover[(i + 2) % cover.size()]);
      const glm::dvec2 e1 = b - a, e2 = c - b;
      if (e1.x * e2.y - e1.y * e2.x < -1e-6 * glm::length(e1) * glm::length(e2)) ++concave;
    }
    // Points of the face: barycentric mixes of its corners, a point at infinity taken far out.
    for (int k = 0; k < 200; ++k) {
      double w[4] = {t01(rng), t01(rng), t01(rng), kind == 2 ? t01(rng) : 0.0};
      if (k % 4 == 0) w[k / 4 % n] = 0.0;  // on an edge
      const double sum = w[0] + w[1] + w[2] + w[3];
      // A side's points at infinity taken far out along the side, a far cap's as directions.
      glm::dvec3 x(0.0);
      for (int i = 0; i < n; ++i) {
        const glm::dvec3 p = glm::dvec3(corners[i]);
        x += w[i] / sum * (kind == 1 ? p - view.light : corners[i].w != 0.0 ? p : p + 1e3 * (p - view.light));
      }
      const glm::dvec4 clip = view.clipFromWorld * glm::dvec4(x, kind == 1 ? 0.0 : 1.0);
      if (clip.w < 2.0 * view.clipNear) continue;
      const glm::dvec2 win = glm::dvec2(clip.x / clip.w * 0.5 + 0.5, -clip.y / clip.w * 0.5 + 0.5) * view.viewport;
      if (win.x < -1.0 || win.y < -1.0 || win.x > view.viewport.x + 1.0 || win.y > view.viewport.y + 1.0) continue;
      ++points;
      // A cover that holds no pixel centre is not drawn: then no pixel centre may lie within the
      // margin of the point either.
      const bool centreNear = std::floor(win.x + view.margin - 0.5) >= std::ceil(win.x - view.margin - 0.5) &&
                              std::floor(win.y + view.margin - 0.5) >= std::ceil(win.y - view.margin - 0.5);
      if (cover.empty() ? centreNear : !holds(cover, win, 0.99 * view.margin)) {
        if (missed < 5) {
          std::printf("kind %d win %g %g cover", kind, win.x, win.y);
          for (auto q : cover) std::printf(" (%g %g)", q.x, q.y);
          std::printf(" w %g\n", clip.w);
        }
        ++missed;
      }
    }
  }
  EXPECT_EQ(missed, 0) << "of " << points << " face points on screen";
  EXPECT_EQ(concave, 0);
  EXPECT_GT(points, 10000);
}

}  // namespace
}  // namespace penumbra
