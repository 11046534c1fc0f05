// The OpenMesh half-edge mesh that EdgeTopology is built from (the rule is in silhouette.h,
// "The silhouette mesh"). Only geometry/ sources and tests include this header: the rest of the
// program reads EdgeTopology's flat arrays and does not compile OpenMesh.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <glm/glm.hpp>

namespace penumbra::geo {

// Double-precision points and normals; the float positions of a mesh convert exactly.
struct SilhouetteTraits : OpenMesh::DefaultTraitsDouble {};
using SilhouetteTriMesh = OpenMesh::TriMesh_ArrayKernelT<SilhouetteTraits>;

struct HalfEdgeMesh {
  // Vertex i < weldedCount is welded vertex i; the vertices after it are the copies made for
  // the refused faces, three per face in refused order.
  SilhouetteTriMesh mesh;
  std::size_t weldedCount = 0;
  std::vector<std::uint32_t> weldedOf;    // OpenMesh vertex -> welded vertex
  std::vector<std::int32_t> faceOf;       // triangle -> OpenMesh face, -1 if it collapsed under welding
  std::vector<std::uint32_t> triangleOf;  // OpenMesh face -> triangle
  std::vector<std::uint32_t> refused;     // triangles refused and added on copies, in input order
  // Welded edge g (sorted by welded end points, as EdgeTopology::edges) is the OpenMesh edges
  // [edgeGroups[g], edgeGroups[g + 1]): the one of its kept faces, then one per refused face.
  std::vector<std::uint32_t> edgeGroups;

  std::size_t duplicatedVertices() const { return weldedOf.size() - weldedCount; }
  std::uint32_t welded(OpenMesh::VertexHandle v) const { return weldedOf[std::size_t(v.idx())]; }
  // The halfedge of face f that leaves the vertex of the triangle's corner `corner` (0, 1, 2).
  OpenMesh::HalfedgeHandle cornerHalfedge(OpenMesh::FaceHandle f, const glm::uvec3& tri, int corner) const;
};

// The half-edge mesh of welded triangles (silhouette.h, "The silhouette mesh"). A triangle that
// collapses under welding has no face. A face is refused where OpenMesh's add_face, adding the
// triangles in order, refuses one: a complex edge (an earlier kept face already runs one of its
// edges the same way: a third face on an edge, or a neighbour wound the other way) or a complex
// vertex (a closed fan and another fan at one vertex: the closed fan with the earliest triangle
// stays). Refused faces are added after all others, each on three fresh copies of its
// vertices, as OpenMesh's importer does (ImporterT::finish). Deterministic; linear apart from
// the sorts within a vertex's fan.
std::shared_ptr<HalfEdgeMesh> buildHalfEdgeMesh(const std::vector<glm::vec3>& weldedPositions,
                                                const std::vector<glm::uvec3>& weldedTriangles);

}  // namespace penumbra::geo
