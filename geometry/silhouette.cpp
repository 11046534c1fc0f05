// Point-light silhouettes as signed edge multiplicities of the per-triangle shadow frusta (see
// silhouette.h). Both rules share one pass: cap signs first, then one sum per edge.
#include "geometry/silhouette.h"

#include <algorithm>
#include <cmath>

namespace penumbra::geo {

VolumeRule volumeRuleFor(const EdgeTopology& topology) {
  return topology.closed ? VolumeRule::ClosedFrontFaces : VolumeRule::PerTriangle;
}

namespace {

// Cap sign c_t from the side (+1, -1, 0) of the light relative to the triangle's plane.
std::int8_t capSignFor(int facing, VolumeRule rule) {
  return static_cast<std::int8_t>(rule == VolumeRule::ClosedFrontFaces ? (facing > 0 ? 1 : 0) : facing);
}

// Unnormalised plane normal of welded triangle t (double precision, in its own winding), as
// the half-edge mesh gave it (EdgeTopology::faceNormals), and its first corner p0.
glm::dvec3 triangleNormal(const EdgeTopology& topology, std::size_t t, glm::dvec3& p0) {
  p0 = glm::dvec3(topology.weldedPositions[topology.weldedTriangles[t].x]);
  return topology.faceNormals[t];
}

// m_e = sum over incident triangles of c_t * orientation.
std::int32_t edgeMultiplicity(const EdgeTopology& topology, const EdgeTopology::Edge& edge,
                              const std::vector<std::int8_t>& capSign) {
  std::int32_t m = 0;
  for (std::uint32_t k = 0; k < edge.incidenceCount; ++k) {
    const EdgeTopology::Incidence& inc = topology.incidences[edge.firstIncidence + k];
    m += capSign[inc.triangle] * inc.orientation;
  }
  return m;
}

}  // namespace

PointSilhouette extractPointSilhouette(const EdgeTopology& topology, const glm::dvec3& light, VolumeRule rule) {
  PointSilhouette out;
  out.capSign.resize(topology.weldedTriangles.size());
  // Facing is decided once per triangle and reused by caps and sides alike, so a triangle
  // edge-on to the light cannot be front for one and back for the other (hard case 9).
  for (std::size_t t = 0; t < topology.weldedTriangles.size(); ++t) {
    glm::dvec3 p0;
    const glm::dvec3 n = triangleNormal(topology, t, p0);  // sets p0: evaluate before using it
    const double d = glm::dot(n, light - p0);
    out.capSign[t] = capSignFor((d > 0.0) - (d < 0.0), rule);
  }
  // Open and non-manifold edges need no special case: the sum handles any incidence count
  // (hard cases 4-7).
  for (std::size_t e = 0; e < topology.edges.size(); ++e) {
    const std::int32_t m = edgeMultiplicity(topology, topology.edges[e], out.capSign);
    if (m != 0) out.sides.push_back({static_cast<std::uint32_t>(e), m});
  }
  return out;
}

int classifyLight(const LightExtent& light, const glm::dvec3& normal, const glm::dvec3& point) {
  const double len = glm::length(normal);
  if (!(len > 0.0)) return 0;
  const glm::dvec3 n = normal / len;
  const double centre = glm::dot(n, light.centre - point);
  double extent = 0.0;
  switch (light.kind) {
    case LightExtent::Kind::Point:
      break;
    case LightExtent::Kind::Rect:
      extent = light.halfWidth * std::abs(glm::dot(n, light.tangent)) +
               light.halfHeight * std::abs(glm::dot(n, light.bitangent));
      break;
    case LightExtent::Kind::Disk: {
      const double c = glm::dot(n, light.normal);
      extent = light.radius * std::sqrt(std::max(0.0, 1.0 - c * c));
      break;
    }
    case LightExtent::Kind::Sphere:
      extent = light.radius;
      break;
  }
  if (centre > extent) return 1;
  if (centre < -extent) return -1;
  return 0;
}

std::vector<std::uint32_t> extractAccurateSilhouette(const EdgeTopology& topology, const LightExtent& light,
                                                     VolumeRule rule) {
  // Per triangle: the light's side of its plane; 0 marks planes that touch or cut the light.
  std::vector<std::int8_t> side(topology.weldedTriangles.size()), capSign(side.size());
  for (std::size_t t = 0; t < side.size(); ++t) {
    glm::dvec3 p0;
    const glm::dvec3 n = triangleNormal(topology, t, p0);  // sets p0: evaluate before using it
    side[t] = static_cast<std::int8_t>(classifyLight(light, n, p0));
    capSign[t] = capSignFor(side[t], rule);
  }
  std::vector<std::uint32_t> out;
  for (std::size_t e = 0; e < topology.edges.size(); ++e) {
    const EdgeTopology::Edge& edge = topology.edges[e];
    bool cut = false;
    for (std::uint32_t k = 0; k < edge.incidenceCount && !cut; ++k)
      cut = side[topology.incidences[edge.firstIncidence + k].triangle] == 0;
    if (cut || edgeMultiplicity(topology, edge, capSign) != 0) out.push_back(static_cast<std::uint32_t>(e));
  }
  return out;
}

}  // namespace penumbra::geo

namespace penumbra::geo {
namespace {

constexpr double kPi = 3.14159265358979323846;

int signOf(double v) { return (v > 0.0) - (v < 0.0); }

// The facing of triangle t at x, as extractPointSilhouette computes it.
int facingAt(const EdgeTopology& topology, std::size_t t, const glm::dvec3& x) {
  glm::dvec3 p0;
  const glm::dvec3 n = triangleNormal(topology, t, p0);
  return signOf(glm::dot(n, x - p0));
}

// Sign test of one triangle edge u -> v that is zero: claimed by the triangle that runs the edge
// from its lower to its higher welded index (the shared-edge tie-break of silhouette.h).
bool claims(std::uint32_t u, std::uint32_t v) { return u < v; }

// x in the plane of triangle t: inside it, or on its border. `inclusive`: every border point
// counts; otherwise the shared-edge tie-break decides (vertices: both edges must claim).
bool inTriangle(const EdgeTopology& topology, std::size_t t, const glm::dvec3& x, bool inclusive) {
  const glm::uvec3& tri = topology.weldedTriangles[t];
  const std::vector<glm::vec3>& P = topology.weldedPositions;
  const std::uint32_t idx[3] = {tri.x, tri.y, tri.z};
  glm::dvec3 p0;
  const glm::dvec3 n = triangleNormal(topology, t, p0);
  if (!(glm::dot(n, n) > 0.0)) return false;  // degenerate: no surface
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3 a(P[idx[i]]), b(P[idx[(i + 1) % 3]]);
    const double side = glm::dot(n, glm::cross(b - a, x - a));
    if (side < 0.0) return false;
    if (side == 0.0 && !inclusive && !claims(idx[i], idx[(i + 1) % 3])) return false;
  }
  return true;
}

}  // namespace

PointLocation locatePoint(const EdgeTopology& topology, const glm::dvec3& x) {
  PointLocation out;
  const std::vector<glm::vec3>& P = topology.weldedPositions;
  if (P.empty()) return out;
  glm::dvec3 lo(P[0]), hi(P[0]);
  for (const glm::vec3& p : P) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
  if (glm::any(glm::lessThan(x, lo)) || glm::any(glm::greaterThan(x, hi))) return out;
  double solidAngle = 0.0;
  for (std::size_t t = 0; t < topology.weldedTriangles.size(); ++t) {
    if (facingAt(topology, t, x) == 0 && inTriangle(topology, t, x, true)) {
      out.onSurface = true;
      return out;
    }
    const glm::uvec3& tri = topology.weldedTriangles[t];
    const glm::dvec3 a = glm::dvec3(P[tri.x]) - x, b = glm::dvec3(P[tri.y]) - x, c = glm::dvec3(P[tri.z]) - x;
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    // Van Oosterom and Strackee (1983): tan(omega / 2) = det(a, b, c) / (|a||b||c| + ...).
    const double det = glm::dot(a, glm::cross(b, c));
    const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
    solidAngle += 2.0 * std::atan2(det, den);
  }
  out.winding = int(std::lround(solidAngle / (4.0 * kPi)));
  return out;
}

int triangleFacing(const EdgeTopology& topology, std::uint32_t t, const glm::dvec3& x) {
  return facingAt(topology, t, x);
}

bool onTriangleBorder(const EdgeTopology& topology, const glm::dvec3& x) {
  for (std::uint32_t t : trianglesNearBall(topology, x, 0.0)) {
    if (facingAt(topology, t, x) != 0 || !inTriangle(topology, t, x, true)) continue;
    const glm::uvec3& tri = topology.weldedTriangles[t];
    const std::vector<glm::vec3>& P = topology.weldedPositions;
    const std::uint32_t idx[3] = {tri.x, tri.y, tri.z};
    glm::dvec3 p0;
    const glm::dvec3 n = triangleNormal(topology, t, p0);
    for (int i = 0; i < 3; ++i) {
      const glm::dvec3 a(P[idx[i]]), b(P[idx[(i + 1) % 3]]);
      if (glm::dot(n, glm::cross(b - a, x - a)) == 0.0) return true;
    }
  }
  return false;
}

std::vector<std::uint32_t> trianglesNearBall(const EdgeTopology& topology, const glm::dvec3& centre, double radius) {
  std::vector<std::uint32_t> out;
  const std::vector<glm::vec3>& P = topology.weldedPositions;
  for (std::size_t t = 0; t < topology.weldedTriangles.size(); ++t) {
    const glm::uvec3& tri = topology.weldedTriangles[t];
    const glm::dvec3 a(P[tri.x]), b(P[tri.y]), c(P[tri.z]);
    const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    // Box around the ball, grown by a relative 1e-9 (rounding of the corners), against the
    // triangle's box; then the ball against the triangle's plane.
    const double r = radius * (1.0 + 1e-9);
    if (glm::any(glm::lessThan(hi, centre - r)) || glm::any(glm::greaterThan(lo, centre + r))) continue;
    glm::dvec3 p0;
    const glm::dvec3 n = triangleNormal(topology, t, p0);
    const double len = glm::length(n);
    if (!(len > 0.0)) continue;
    if (std::abs(glm::dot(n, centre - p0)) > r * len) continue;
    out.push_back(std::uint32_t(t));
  }
  return out;
}

std::optional<int> windingAtPathEnd(int atC, std::span<const PathCrossing> crossings) {
  int w = atC;
  for (const PathCrossing& x : crossings) {
    if (x.sideS == 0) return std::nullopt;
    w += x.sideC > 0 && x.sideS < 0 ? 1 : (x.sideC < 0 && x.sideS > 0 ? -1 : 0);
  }
  return w;
}

bool pathMeetsSegment(const EdgeTopology& topology, std::uint32_t t, const glm::dvec3& u, const glm::dvec3& v,
                      const glm::dvec3& c, const glm::dvec3& s) {
  const glm::dvec3& n = topology.faceNormals[t];
  auto orient = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& x) {
    return signOf(glm::dot(n, glm::cross(b - a, x - a)));
  };
  const int oc = orient(u, v, c), os = orient(u, v, s), ou = orient(c, s, u), ov = orient(c, s, v);
  if (oc == 0 && os == 0) {  // on one line: the intervals along it overlap
    const glm::dvec3 d = v - u;
    double lo = glm::dot(c - u, d), hi = glm::dot(s - u, d);
    if (lo > hi) std::swap(lo, hi);
    return hi >= 0.0 && lo <= glm::dot(d, d);
  }
  return oc * os <= 0 && ou * ov <= 0;
}

std::size_t findEdge(const EdgeTopology& topology, std::uint32_t a, std::uint32_t b) {
  const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
  const auto it = std::lower_bound(topology.edges.begin(), topology.edges.end(), std::pair{lo, hi},
                                   [](const EdgeTopology::Edge& e, const std::pair<std::uint32_t, std::uint32_t>& k) {
                                     return std::pair{e.v0, e.v1} < k;
                                   });
  return it != topology.edges.end() && it->v0 == lo && it->v1 == hi ? std::size_t(it - topology.edges.begin())
                                                                    : topology.edges.size();
}

void pathCrossings(const EdgeTopology& topology, const std::vector<std::uint32_t>& candidates, const glm::dvec3& c,
                   const glm::dvec3& s, std::vector<PathCrossing>& out) {
  const std::vector<glm::vec3>& P = topology.weldedPositions;
  for (std::uint32_t t : candidates) {
    const int sc = facingAt(topology, t, c), ss = facingAt(topology, t, s);
    if (sc == ss) continue;  // same side, or the whole path in the plane: no crossing
    bool crosses = false;
    if (sc == 0) {
      crosses = inTriangle(topology, t, c, false);
    } else if (ss == 0) {
      crosses = inTriangle(topology, t, s, false);
    } else {
      // The path meets the plane inside t when it passes the three edges on the same hand:
      // orient(c, s, u, v) of one sign for every edge u -> v (zero: the shared-edge tie-break).
      const glm::uvec3& tri = topology.weldedTriangles[t];
      const std::uint32_t idx[3] = {tri.x, tri.y, tri.z};
      int hand = 0;
      crosses = true;
      for (int i = 0; i < 3 && crosses; ++i) {
        const glm::dvec3 u(P[idx[i]]), v(P[idx[(i + 1) % 3]]);
        const int o = signOf(glm::dot(glm::cross(s - c, u - c), v - c));
        if (o == 0) {
          crosses = claims(idx[i], idx[(i + 1) % 3]);
        } else if (hand == 0) {
          hand = o;
        } else {
          crosses = o == hand;
        }
      }
    }
    if (crosses) out.push_back({t, std::int8_t(sc), std::int8_t(ss)});
  }
}

}  // namespace penumbra::geo
