// Silhouette edges and shadow-volume caps for a point light (the centre of an area light).
//
// The shadow volume of a mesh for light position l is the set of points q such that the segment
// l -> q crosses the mesh. We build it from per-triangle volumes: triangle t with
// cap sign c_t contributes the semi-infinite frustum behind it (near cap = t, far cap = t
// projected to infinity, three sides). Sides of adjacent frusta cancel where they coincide, so
// only edges with non-zero multiplicity m_e = sum over incident t of c_t * orientation_t(e)
// need a side quad, drawn with weight m_e. Two rules choose c_t:
//
//  * ClosedFrontFaces (closed, consistently wound meshes): c_t = 1 if t faces l, else 0. The
//    classic rule: m_e is +-1 on silhouettes, the count is the number of closed objects crossed.
//  * PerTriangle (open, non-manifold or inconsistently wound meshes): c_t = sign(facing), so
//    every triangle occludes whichever side faces the light; the count is the number of
//    surfaces crossed. It does not depend on the winding at all (flipping t flips both factors).
//
// facing_t = sign(dot(cross(p1-p0, p2-p0), l - p0)) in double precision, computed once per
// triangle and used for both caps and sides, so no crack can open between them (hard case 9).
// A triangle edge-on to the light has facing 0 and contributes nothing (its frustum is empty).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/mesh.h"

namespace penumbra::geo {

enum class VolumeRule { ClosedFrontFaces, PerTriangle };

// The rule a mesh needs: ClosedFrontFaces when topology.closed, PerTriangle otherwise.
VolumeRule volumeRuleFor(const EdgeTopology& topology);

struct PointSilhouette {
  struct SideEdge {
    std::uint32_t edge;      // index into EdgeTopology::edges
    std::int32_t multiplicity;  // m_e != 0; sign relative to the edge's v0 -> v1 direction
  };
  std::vector<SideEdge> sides;
  std::vector<std::int8_t> capSign;  // c_t per triangle (-1, 0, +1)
};

PointSilhouette extractPointSilhouette(const EdgeTopology& topology, const glm::dvec3& light,
                                       VolumeRule rule);

}  // namespace penumbra::geo
