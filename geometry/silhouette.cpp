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

// Unnormalised plane normal of welded triangle t (double precision, in its own winding).
glm::dvec3 triangleNormal(const EdgeTopology& topology, std::size_t t, glm::dvec3& p0) {
  const std::vector<glm::vec3>& p = topology.weldedPositions;
  const glm::uvec3& tri = topology.weldedTriangles[t];
  p0 = glm::dvec3(p[tri.x]);
  return glm::cross(glm::dvec3(p[tri.y]) - p0, glm::dvec3(p[tri.z]) - p0);
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

PointSilhouette extractPointSilhouette(const EdgeTopology& topology, const glm::dvec3& light,
                                       VolumeRule rule) {
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
    case LightExtent::Kind::Point: break;
    case LightExtent::Kind::Rect:
      extent = light.halfWidth * std::abs(glm::dot(n, light.tangent)) +
               light.halfHeight * std::abs(glm::dot(n, light.bitangent));
      break;
    case LightExtent::Kind::Disk: {
      const double c = glm::dot(n, light.normal);
      extent = light.radius * std::sqrt(std::max(0.0, 1.0 - c * c));
      break;
    }
    case LightExtent::Kind::Sphere: extent = light.radius; break;
  }
  if (centre > extent) return 1;
  if (centre < -extent) return -1;
  return 0;
}

std::vector<std::uint32_t> extractAccurateSilhouette(const EdgeTopology& topology,
                                                     const LightExtent& light, VolumeRule rule) {
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
