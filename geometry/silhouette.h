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
//
// The silhouette mesh (buildEdgeTopology, geometry/half_edge_mesh.h). Vertices are welded by
// exact position (-0 = +0), so split-normal and split-UV copies share edges. The welded
// triangles form an OpenMesh TriMesh with double-precision points; one that collapses under
// welding (two corners at one position) has no face. In triangle order, a face is refused where
// OpenMesh's add_face would refuse it: a complex edge (an earlier face already runs one of its
// edges the same way: a third triangle on an edge, or a neighbour wound the other way) or a
// complex vertex (a closed fan beside another fan at one vertex; the closed fan with the
// earliest triangle stays). The refused faces are added after all others, each on three fresh
// copies of its vertices, as OpenMesh's importer does; MeshReport::duplicatedVertices counts
// the copies (3 per refused face). The edges of EdgeTopology are the OpenMesh edges grouped by
// the welded ids of their end points, so a copy's edge joins the edge it copies and m_e sums
// over every triangle on the welded edge, exactly as over a triangle soup: a non-manifold edge
// keeps all its incidences (the book's spine: 3), and the closed test (2 opposite incidences on
// every welded edge) does not depend on the refusals (two closed boxes touching at a corner stay
// closed). The face normals are read from the faces' halfedges (cross of the edges leaving the
// first corner), the same doubles as from the positions, so the facings below are unchanged.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/mesh.h"

namespace penumbra::geo {

enum class VolumeRule { ClosedFrontFaces, PerTriangle };

// The rule a mesh needs: ClosedFrontFaces when topology.closed, PerTriangle otherwise.
VolumeRule volumeRuleFor(const EdgeTopology& topology);

struct PointSilhouette {
  struct SideEdge {
    std::uint32_t edge;         // index into EdgeTopology::edges
    std::int32_t multiplicity;  // m_e != 0; sign relative to the edge's v0 -> v1 direction
  };
  std::vector<SideEdge> sides;
  std::vector<std::int8_t> capSign;  // c_t per triangle (-1, 0, +1)
};

PointSilhouette extractPointSilhouette(const EdgeTopology& topology, const glm::dvec3& light, VolumeRule rule);

}  // namespace penumbra::geo

namespace penumbra::geo {

// The extent of a light for accurate silhouettes (DCS paper 4.4, after Laine et al. 2005): a
// rectangle (half sizes along tangent and bitangent), a disk (radius, in the tangent plane), a
// ball (radius) or a point.
struct LightExtent {
  enum class Kind { Point, Rect, Disk, Sphere };
  Kind kind = Kind::Point;
  glm::dvec3 centre{0.0}, normal{0, -1, 0}, tangent{1, 0, 0}, bitangent{0, 0, 1};
  double halfWidth = 0.0, halfHeight = 0.0;  // rect
  double radius = 0.0;                       // disk, sphere
};

// Where the light lies against the plane through `point` with normal `normal`: +1 entirely on
// the positive side, -1 entirely on the negative side, 0 touching or straddling it.
int classifyLight(const LightExtent& light, const glm::dvec3& normal, const glm::dvec3& point);

// Accurate silhouette: the edges whose multiplicity m_e is non-zero for some point of the light.
// An edge qualifies when the plane of an incident triangle touches or cuts the light (it is a
// silhouette for part of the light), or when the light lies on fixed sides of all incident
// planes and m_e (as in extractPointSilhouette, with those sides as facings) is non-zero. The
// standard silhouette is extractPointSilhouette from the light centre: it misses the first kind
// and so underestimates penumbrae (DCS paper Fig. 4). Sorted edge indices.
std::vector<std::uint32_t> extractAccurateSilhouette(const EdgeTopology& topology, const LightExtent& light,
                                                     VolumeRule rule);

}  // namespace penumbra::geo

namespace penumbra::geo {

// Lights touching or inside closed meshes (hard cases 27-29). Every test is in double on the
// welded positions, with the facing expression of extractPointSilhouette, so "a point exactly on
// a triangle's plane" means exactly what facing 0 means for the shadow volumes.
//
// Convention for a light point exactly on a surface: the surface it lies on does not occlude it
// (its triangles have facing 0 and no volume; the reference's ray stops 1e-5 short of the
// sample); the rest of the mesh does. Tie-break on a shared edge (a point or a segment exactly
// through an edge shared by two triangles): the triangle that runs the edge from its lower to
// its higher welded index claims it, so a flat face split into triangles counts once.

// Where x lies against a mesh: on a triangle (its plane through x, x inside it or on its border),
// else the winding number (generalised, Van Oosterom-Strackee solid angles, rounded: 1 inside a
// closed mesh wound outwards, 0 outside, -1 inside an inverted one). Points outside the mesh's
// bounding box are 0 without the solid-angle sum.
struct PointLocation {
  bool onSurface = false;
  int winding = 0;
};
PointLocation locatePoint(const EdgeTopology& topology, const glm::dvec3& x);

// Where the straight path from c to s passes through a triangle (an endpoint on the triangle
// counts, with side 0): what the depth complexity of a path from the light centre gains or loses
// besides the edge crossings (techniques/shadow_volume, dcs). `sideC`/`sideS` are the signs of
// the triangle's facing at c and s (+1 on the side its normal points to).
struct PathCrossing {
  std::uint32_t triangle;
  std::int8_t sideC, sideS;
};
// The facing of triangle t at x as extractPointSilhouette decides it: +1, -1, 0 in its plane.
int triangleFacing(const EdgeTopology& topology, std::uint32_t t, const glm::dvec3& x);
// x lies exactly on an edge or a vertex of some triangle (in its plane, on its border): where a
// path starting at x meets the surface at a border, which the crossings above do not resolve.
bool onTriangleBorder(const EdgeTopology& topology, const glm::dvec3& x);
// The triangles that can meet a path inside the ball (centre, radius): a cheap filter.
std::vector<std::uint32_t> trianglesNearBall(const EdgeTopology& topology, const glm::dvec3& centre, double radius);
// Appends the crossings of the path c -> s with the candidate triangles.
void pathCrossings(const EdgeTopology& topology, const std::vector<std::uint32_t>& candidates, const glm::dvec3& c,
                   const glm::dvec3& s, std::vector<PathCrossing>& out);
// The winding number at the end s of a path from c, from the winding `atC` at c and the path's
// crossings (pathCrossings): plus one per entry from the side the normals point to, minus one per
// exit; nullopt when the path ends on the surface (s lies in no cell).
std::optional<int> windingAtPathEnd(int atC, std::span<const PathCrossing> crossings);
// For c and s in the plane of triangle t (facing 0 at both): the path c -> s meets the closed
// segment u -> v of that plane (crosses it, touches it, or runs along it). A path along a
// surface across the surface's border is where the crossings above and the volumes' edge events
// coincide and are not resolved (dcs refuses it). Orientation tests with t's normal, in double.
bool pathMeetsSegment(const EdgeTopology& topology, std::uint32_t t, const glm::dvec3& u, const glm::dvec3& v,
                      const glm::dvec3& c, const glm::dvec3& s);
// The edge with welded end points a and b (either order), or edges.size().
std::size_t findEdge(const EdgeTopology& topology, std::uint32_t a, std::uint32_t b);

}  // namespace penumbra::geo
