// Point-light silhouettes as signed edge multiplicities of the per-triangle shadow frusta (see
// silhouette.h). Both rules share one pass: cap signs first, then one sum per edge.
#include "geometry/silhouette.h"

namespace penumbra::geo {

VolumeRule volumeRuleFor(const EdgeTopology& topology) {
  return topology.closed ? VolumeRule::ClosedFrontFaces : VolumeRule::PerTriangle;
}

PointSilhouette extractPointSilhouette(const EdgeTopology& topology, const glm::dvec3& light,
                                       VolumeRule rule) {
  PointSilhouette out;
  const std::vector<glm::vec3>& p = topology.weldedPositions;
  out.capSign.resize(topology.weldedTriangles.size());
  // Facing is decided once per triangle and reused by caps and sides alike, so a triangle
  // edge-on to the light cannot be front for one and back for the other (hard case 9).
  for (std::size_t t = 0; t < topology.weldedTriangles.size(); ++t) {
    const glm::uvec3& tri = topology.weldedTriangles[t];
    const glm::dvec3 p0(p[tri.x]);
    const glm::dvec3 n = glm::cross(glm::dvec3(p[tri.y]) - p0, glm::dvec3(p[tri.z]) - p0);
    const double d = glm::dot(n, light - p0);
    const int facing = (d > 0.0) - (d < 0.0);
    out.capSign[t] = static_cast<std::int8_t>(
        rule == VolumeRule::ClosedFrontFaces ? (facing > 0 ? 1 : 0) : facing);
  }
  // Open and non-manifold edges need no special case: the sum handles any incidence count
  // (hard cases 4-7).
  for (std::size_t e = 0; e < topology.edges.size(); ++e) {
    const EdgeTopology::Edge& edge = topology.edges[e];
    std::int32_t m = 0;
    for (std::uint32_t k = 0; k < edge.incidenceCount; ++k) {
      const EdgeTopology::Incidence& inc = topology.incidences[edge.firstIncidence + k];
      m += out.capSign[inc.triangle] * inc.orientation;
    }
    if (m != 0) out.sides.push_back({static_cast<std::uint32_t>(e), m});
  }
  return out;
}

}  // namespace penumbra::geo
