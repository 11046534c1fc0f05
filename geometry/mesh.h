// CPU triangle meshes, their validation report and edge topology. No GL here.
//
// Conventions: positions in the mesh's own space (world space once a scene is loaded);
// triangles are counter-clockwise when seen from the side their geometric normal points to.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace penumbra::geo {

struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty or one per position
  std::vector<glm::vec2> uvs;      // empty or one per position
  std::vector<glm::uvec3> triangles;
};

// What loading and cleaning did to a mesh. Nothing a user gave is dropped silently: every
// dropped or changed face is counted here and printed by `penumbra info`.
struct MeshReport {
  std::size_t inputVertices = 0;
  std::size_t inputFaces = 0;            // faces as written in the file (polygons count once)
  std::size_t triangles = 0;             // triangles kept
  std::size_t polygonsTriangulated = 0;  // faces with > 3 vertices fanned into triangles
  std::size_t droppedInvalidIndex = 0;   // index out of range
  std::size_t droppedDegenerate = 0;     // repeated vertex index or zero area
  std::size_t droppedNonFinite = 0;      // a NaN/Inf vertex position
  std::size_t droppedDuplicate = 0;      // same vertex set as an earlier face
  std::size_t duplicatedVertices = 0;    // vertex copies for faces OpenMesh's add_face refused (silhouette.h)
  std::size_t hugeCoordinates = 0;       // |coordinate| > 1e6 (kept, warned)
  std::size_t openEdges = 0;             // edges with one incident triangle
  std::size_t nonManifoldEdges = 0;      // edges with > 2 incident triangles
  std::size_t inconsistentEdges = 0;     // two-triangle edges traversed in the same direction
  std::size_t components = 0;            // edge-connected components
  bool closed = false;                   // every edge has two oppositely oriented triangles
  std::size_t ignoredElements = 0;       // line and point elements (OBJ `l`, `p`; PLY edges): not surfaces
  bool vertexColours = false;  // colours per vertex in the file (OBJ `v x y z r g b`, PLY red/green/blue): not shaded

  std::size_t droppedTotal() const {
    return droppedInvalidIndex + droppedDegenerate + droppedNonFinite + droppedDuplicate;
  }
  // What a loader must say: something dropped, ignored or unusual in the file.
  bool worthWarning() const {
    return droppedTotal() > 0 || hugeCoordinates > 0 || ignoredElements > 0 || vertexColours;
  }
  // One line: "12 triangles, 0 dropped, 4 open edges, ..." (only non-zero counts beyond the first).
  std::string summary() const;
};

struct HalfEdgeMesh;  // geometry/half_edge_mesh.h: the OpenMesh TriMesh these arrays come from

// Edge topology over vertices welded by exact position (so split-normal or split-UV vertices
// share edges), read from an OpenMesh half-edge mesh (silhouette.h, "The silhouette mesh").
// Works for any topology: open, non-manifold, inconsistently wound.
struct EdgeTopology {
  struct Incidence {
    std::uint32_t triangle;
    std::int8_t orientation;  // +1 if the triangle traverses v0 -> v1, -1 if v1 -> v0
  };
  struct Edge {
    std::uint32_t v0, v1;  // welded vertex ids, v0 < v1
    std::uint32_t firstIncidence, incidenceCount;
  };
  std::vector<glm::vec3> weldedPositions;   // one per welded vertex
  std::vector<std::uint32_t> weldedIndex;   // input vertex -> welded vertex
  std::vector<glm::uvec3> weldedTriangles;  // triangles over welded vertices
  std::vector<Edge> edges;                  // sorted by (v0, v1)
  std::vector<Incidence> incidences;        // per edge sorted by (triangle, orientation)
  // Per triangle: cross(p1 - p0, p2 - p0) in double over the welded positions (p0 the first
  // corner), unnormalised, read from the face's halfedges; zero for a triangle that collapses
  // under welding. The facing of silhouette.h is the sign of its dot product with l - p0.
  std::vector<glm::dvec3> faceNormals;
  std::shared_ptr<const HalfEdgeMesh> halfEdges;  // the OpenMesh mesh (shared by copies)
  std::size_t duplicatedVertices = 0;             // vertex copies made for refused faces
  bool closed = false;                            // every edge: exactly 2 incidences with opposite orientation
};

// Drops invalid, degenerate, non-finite and duplicate triangles (counting each in `report`),
// then fills the topology counts of `report`. Keeps vertex arrays; unused vertices stay.
void cleanMesh(TriangleMesh& mesh, MeshReport& report);

// Builds the welded edge topology of a cleaned mesh.
EdgeTopology buildEdgeTopology(const TriangleMesh& mesh);

// Shading normals, one per triangle corner (3 per triangle, in triangle order): at each corner
// the angle-weighted sum (Thürmer and Wüthrich 1998) of the unit normals of the faces reached
// around the corner's vertex on the half-edge mesh without crossing a crease, normalised. An
// edge is a crease when the angle between its two faces' normals exceeds `creaseAngle`
// (radians; 0: flat shading, pi or more: smooth everywhere), and so is every boundary and every
// edge of a refused face, whose copied vertices join no other face (silhouette.h). Welding by
// position makes split-normal and split-UV vertices one vertex, so seams do not crease. A
// triangle that collapses under welding gets zero normals.
std::vector<glm::vec3> cornerNormals(const EdgeTopology& topology, double creaseAngle);

// The crease angle of computed shading normals: 45 degrees (edges whose faces' normals differ by
// more stay sharp: a cube's edges, a cylinder's rim; a cylinder of 16 segments, 22.5 degrees a
// step, is smooth round its side).
constexpr double kDefaultCreaseAngle = 0.78539816339744831;

// Shading normals for the G-buffer: leaves a mesh that has one normal per
// position (from its file: glTF NORMAL, OBJ vn, PLY nx/ny/nz; or from a primitive) as it is;
// otherwise sets mesh.normals to cornerNormals(buildEdgeTopology(mesh), creaseAngle), splitting
// a vertex where its corners get different normals (the copy takes the position and uv; the
// first corner's normal stays with the original index), so that a crease keeps each side's
// normal. Welding by position (buildEdgeTopology) joins the copies again: silhouettes, volumes
// and the reference are unchanged. Unused vertices get a zero normal. Deterministic.
void ensureShadingNormals(TriangleMesh& mesh, double creaseAngle = kDefaultCreaseAngle);

// Loads OBJ, PLY (ASCII and binary), OFF or STL (ASCII and binary) with penumbra's own parsers,
// which keep every face or count why it was dropped, then cleans the mesh. We do not use
// OpenMesh 9.0's readers here: measured, an ASCII PLY with one `nan` loads 0 faces and zeroes
// every later vertex while reporting success, an ASCII STL with a `nan` keeps a wrong face,
// and a binary PLY list length of 2^32 is reserved before reading (hard-cases.md, bad inputs).
// The tests cross-check our readers against OpenMesh on valid real models. Throws
// penumbra::Error naming the file on a missing/unreadable/unsupported/truncated file, a header
// claiming more data than the file holds, or no triangle left.
TriangleMesh loadMeshFile(const std::string& path, MeshReport& report);

// An OBJ file split by material: the faces after each `usemtl NAME` (the name is the rest of the
// line, spaces included) form one part per name, in order of first use; faces before any
// usemtl form the part with material "". Each part is cleaned and counted on its own (a part
// may be left with no triangles: its report says why). `libraries` are the `mtllib` arguments
// as written. Throws like loadMeshFile, and when no part has a triangle left.
struct ObjPart {
  std::string material;
  TriangleMesh mesh;
  MeshReport report;
};
struct ObjFile {
  std::vector<std::string> libraries;
  std::vector<ObjPart> parts;
};
ObjFile loadObjFile(const std::string& path);

}  // namespace penumbra::geo
