// The OpenMesh TriMesh behind EdgeTopology, and the shading normals computed on its half-edge
// structure. The mesh is built in bulk through the kernel's connectivity setters rather than
// face by face with add_face: add_face costs ~2 us a face here (it searches each vertex's ring
// and checks every handle), which tripled the prepare time of a 235k-triangle scene; the bulk
// build refuses the faces add_face would refuse and links what it keeps as add_face would.
#include "geometry/half_edge_mesh.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "core/error.h"
#include "geometry/bucket_sort.h"
#include "geometry/mesh.h"

namespace penumbra::geo {
namespace {

OpenMesh::Vec3d toOpenMesh(const glm::vec3& p) { return {double(p.x), double(p.y), double(p.z)}; }
glm::dvec3 toGlm(const OpenMesh::Vec3d& p) { return {p[0], p[1], p[2]}; }

constexpr std::uint32_t kNone = 0xffffffffu;

bool collapsed(const glm::uvec3& t) { return t.x == t.y || t.y == t.z || t.z == t.x; }

// Directed edge d = 3t + k runs from corner k to corner k + 1 of triangle t. The direction
// (0: lo -> hi) rides along so the loops over sorted halves need not read the triangle again (a
// cache miss each). Eight bytes a half: most of the build's time is the first touch of its memory.
struct Half {
  std::uint32_t hi;
  std::uint32_t code;  // 2d + direction
  std::uint32_t directed() const { return code >> 1; }
  std::uint32_t triangle() const { return (code >> 1) / 3; }
  std::uint32_t corner() const { return (code >> 1) % 3; }
  int direction() const { return int(code & 1u); }
};

std::uint32_t direction(const glm::uvec3& t, std::uint32_t k) { return t[k] < t[(k + 1) % 3] ? 0u : 1u; }

// The directed edges grouped by welded end points (a group is one welded edge), sorted by
// (lo, hi, triangle, corner).
struct EdgeGroups {
  std::vector<std::uint32_t> bucket;      // lo -> where its halves start (so a half need not hold lo)
  std::vector<Half> halves;               // sorted
  std::vector<std::uint32_t> groupOf;     // directed edge 3t + k -> its group
  std::vector<std::uint32_t> groupStart;  // group -> first sorted half; one past the last half at the end
  std::size_t count() const { return groupStart.size() - 1; }
};

// Made straight into place by a counting sort on lo: a bucket then holds its halves in
// (triangle, corner) order, and a stable insertion sort on hi (a vertex's few edges) finishes
// the order.
EdgeGroups groupEdges(std::size_t vertexCount, const std::vector<glm::uvec3>& tris) {
  EdgeGroups g;
  g.bucket.assign(vertexCount + 1, 0);
  for (const glm::uvec3& t : tris)
    if (!collapsed(t))
      for (std::uint32_t k = 0; k < 3; ++k) ++g.bucket[std::min(t[k], t[(k + 1) % 3]) + 1];
  std::partial_sum(g.bucket.begin(), g.bucket.end(), g.bucket.begin());
  g.halves.resize(g.bucket[vertexCount]);
  {
    std::vector<std::uint32_t> next(g.bucket.begin(), g.bucket.end() - 1);
    for (std::size_t t = 0; t < tris.size(); ++t) {
      if (collapsed(tris[t])) continue;
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t a = tris[t][k], b = tris[t][(k + 1) % 3], lo = std::min(a, b);
        g.halves[next[lo]++] = {std::max(a, b), std::uint32_t(2 * (3 * t + k) + (a < b ? 0 : 1))};
      }
    }
  }
  for (std::size_t v = 0; v < vertexCount; ++v)
    for (std::uint32_t i = g.bucket[v] + 1; i < g.bucket[v + 1]; ++i)
      for (std::uint32_t j = i; j > g.bucket[v] && g.halves[j].hi < g.halves[j - 1].hi; --j)
        std::swap(g.halves[j], g.halves[j - 1]);
  g.groupOf.assign(3 * tris.size(), kNone);
  for (std::size_t v = 0; v < vertexCount; ++v)
    for (std::uint32_t i = g.bucket[v]; i < g.bucket[v + 1]; ++i) {
      if (i == g.bucket[v] || g.halves[i].hi != g.halves[i - 1].hi) g.groupStart.push_back(i);
      g.groupOf[g.halves[i].directed()] = std::uint32_t(g.groupStart.size() - 1);
    }
  g.groupStart.push_back(std::uint32_t(g.halves.size()));
  return g;
}

// The triangles kept, and across each kept directed edge 3t + k the kept one running its
// welded edge the other way (kNone at a boundary).
struct Kept {
  std::vector<std::uint8_t> triangle;
  std::vector<std::uint32_t> twin;
};

// Complex edges, in triangle order: a triangle is refused when an earlier kept one already
// runs one of its edges the same way (add_face: "complex edge"). What is kept is
// edge-manifold: each welded edge has at most one face per direction. Twins are linked as each
// triangle is kept: one look-up per step of the fan walks below instead of three.
Kept keepManifoldEdges(const EdgeGroups& groups, const std::vector<glm::uvec3>& tris) {
  std::vector<std::uint32_t> owner(2 * groups.count(), kNone);  // (group, direction) -> directed edge
  Kept kept{std::vector<std::uint8_t>(tris.size(), 0), std::vector<std::uint32_t>(3 * tris.size(), kNone)};
  for (std::size_t t = 0; t < tris.size(); ++t) {
    if (collapsed(tris[t])) continue;
    bool free = true;
    for (std::uint32_t k = 0; k < 3 && free; ++k)
      free = owner[2 * groups.groupOf[3 * t + k] + direction(tris[t], k)] == kNone;
    if (!free) continue;
    kept.triangle[t] = 1;
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t d = std::uint32_t(3 * t + k), g = groups.groupOf[d], dir = direction(tris[t], k);
      owner[2 * g + dir] = d;
      if (const std::uint32_t other = owner[2 * g + 1 - dir]; other != kNone)
        kept.twin[d] = other, kept.twin[other] = d;
    }
  }
  return kept;
}

// The kept corners at a vertex, joined across shared edges, form its fans (paths or cycles).
struct FanWalker {
  const std::vector<std::uint32_t>& twin;
  // The corner of the same vertex next round it: across the edge leaving it (forward) or arriving at it.
  std::uint32_t step(std::uint32_t corner, bool forward) const {
    const std::uint32_t k = corner % 3, other = twin[corner - k + (forward ? k : (k + 2) % 3)];
    if (other == kNone) return kNone;
    return forward ? 3 * (other / 3) + (other % 3 + 1) % 3 : other;
  }
  // Walks the fan of `corner` and calls visit on each of its corners; returns whether it is closed.
  template <class Visit>
  bool walk(std::uint32_t corner, Visit&& visit) const {
    visit(corner);
    for (std::uint32_t c = step(corner, true); c != kNone; c = step(c, true)) {
      if (c == corner) return true;
      visit(c);
    }
    for (std::uint32_t c = step(corner, false); c != kNone; c = step(c, false)) visit(c);
    return false;
  }
};

// The vertices whose kept corners are not all reached by a walk round the fan of the first.
std::vector<std::uint8_t> verticesWithSeveralFans(std::size_t vertexCount, const std::vector<glm::uvec3>& tris,
                                                  const Kept& kept) {
  std::vector<std::uint32_t> firstCorner(vertexCount, kNone), cornerCount(vertexCount, 0);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    if (!kept.triangle[t]) continue;
    for (std::uint32_t k = 0; k < 3; ++k) {
      if (firstCorner[tris[t][k]] == kNone) firstCorner[tris[t][k]] = std::uint32_t(3 * t + k);
      ++cornerCount[tris[t][k]];
    }
  }
  const FanWalker fans{kept.twin};
  std::vector<std::uint8_t> several(vertexCount, 0);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    if (firstCorner[v] == kNone) continue;
    std::uint32_t reached = 0;
    fans.walk(firstCorner[v], [&](std::uint32_t) { ++reached; });
    several[v] = reached != cornerCount[v];
  }
  return several;
}

// Complex vertices: a half-edge mesh has no room for a closed fan beside another fan at the
// same vertex (add_face: "complex vertex"): there the closed fan with the earliest triangle
// stays, and the triangles of the other fans at that vertex are refused. Only the vertices with
// more than one fan are sorted into fans.
void refuseComplexVertices(std::size_t vertexCount, const std::vector<glm::uvec3>& tris, Kept& kept) {
  const std::vector<std::uint8_t> severalFans = verticesWithSeveralFans(vertexCount, tris, kept);
  if (std::find(severalFans.begin(), severalFans.end(), 1) == severalFans.end()) return;
  std::vector<std::uint32_t> corners;  // the corners at vertices with several fans, by vertex
  for (std::size_t t = 0; t < tris.size(); ++t) {
    if (!kept.triangle[t]) continue;
    for (std::uint32_t k = 0; k < 3; ++k)
      if (severalFans[tris[t][k]]) corners.push_back(std::uint32_t(3 * t + k));
  }
  const auto vertexOf = [&](std::uint32_t c) { return tris[c / 3][c % 3]; };
  corners = bucketSort(corners, vertexCount, vertexOf);
  const FanWalker walker{kept.twin};
  std::vector<std::uint8_t> refuse(tris.size(), 0);
  for (std::size_t i = 0, j = 0; i < corners.size(); i = j) {
    const std::uint32_t v = vertexOf(corners[i]);
    for (j = i; j < corners.size() && vertexOf(corners[j]) == v;) ++j;
    // Label the fans (corners are sorted, so fans come in order of their earliest triangle).
    std::vector<std::uint32_t> label(j - i, kNone);
    const auto slot = [&](std::uint32_t c) {
      return std::size_t(std::lower_bound(corners.begin() + std::ptrdiff_t(i), corners.begin() + std::ptrdiff_t(j), c) -
                         (corners.begin() + std::ptrdiff_t(i)));
    };
    std::uint32_t keep = kNone, fans = 0;
    for (std::size_t c = i; c < j; ++c) {
      if (label[c - i] != kNone) continue;
      const bool closed = walker.walk(corners[c], [&](std::uint32_t x) { label[slot(x)] = fans; });
      if (closed && keep == kNone) keep = fans;
      ++fans;
    }
    if (keep == kNone) continue;  // only open fans: a non-manifold vertex the mesh can hold
    for (std::size_t c = i; c < j; ++c)
      if (label[c - i] != keep) refuse[corners[c] / 3] = 1;
  }
  for (std::size_t t = 0; t < tris.size(); ++t) kept.triangle[t] = kept.triangle[t] && !refuse[t];
}

// Lists the refused triangles and gives each three copies of its vertices after the welded
// ones; returns refused triangle -> its first copy.
std::vector<std::uint32_t> copyRefused(HalfEdgeMesh& out, const std::vector<glm::uvec3>& tris,
                                       const std::vector<std::uint8_t>& kept) {
  for (std::size_t t = 0; t < tris.size(); ++t)
    if (!collapsed(tris[t]) && !kept[t]) out.refused.push_back(std::uint32_t(t));
  std::vector<std::uint32_t> copyOf(tris.size(), kNone);
  out.weldedOf.resize(out.weldedCount);
  std::iota(out.weldedOf.begin(), out.weldedOf.end(), 0u);
  for (std::uint32_t t : out.refused) {
    copyOf[t] = std::uint32_t(out.weldedOf.size());
    for (int k = 0; k < 3; ++k) out.weldedOf.push_back(tris[t][k]);
  }
  return copyOf;
}

// One OpenMesh edge per group with kept faces, one per refused directed edge (on copies).
std::size_t edgeCount(const EdgeGroups& groups, const std::vector<std::uint8_t>& kept) {
  std::size_t count = 0;
  for (std::size_t g = 0; g < groups.count(); ++g) {
    bool shared = false;
    for (std::uint32_t i = groups.groupStart[g]; i < groups.groupStart[g + 1]; ++i) {
      const bool k = kept[groups.halves[i].triangle()];
      shared = shared || k;
      count += !k;
    }
    count += shared;
  }
  return count;
}

// Sets the edges' vertices and out.edgeGroups; writes directed edge -> OpenMesh halfedge.
void linkEdges(HalfEdgeMesh& out, const EdgeGroups& groups, const std::vector<std::uint8_t>& kept,
               const std::vector<std::uint32_t>& copyOf, std::vector<std::uint32_t>& halfedgeOf) {
  SilhouetteTriMesh& m = out.mesh;
  out.edgeGroups.reserve(groups.count() + 1);
  int edge = 0;
  std::uint32_t lo = 0;  // the group's lower end point: the bucket its first half lies in
  for (std::size_t g = 0; g < groups.count(); ++g) {
    while (groups.bucket[lo + 1] <= groups.groupStart[g]) ++lo;
    out.edgeGroups.push_back(std::uint32_t(edge));
    OpenMesh::EdgeHandle sharedEdge;
    for (std::uint32_t i = groups.groupStart[g]; i < groups.groupStart[g + 1]; ++i) {
      const Half& h = groups.halves[i];
      const std::uint32_t t = h.triangle();
      if (kept[t]) {
        if (!sharedEdge.is_valid()) {  // halfedge 0 runs lo -> hi
          sharedEdge = OpenMesh::EdgeHandle(edge++);
          m.set_vertex_handle(m.halfedge_handle(sharedEdge, 0), OpenMesh::VertexHandle(int(h.hi)));
          m.set_vertex_handle(m.halfedge_handle(sharedEdge, 1), OpenMesh::VertexHandle(int(lo)));
        }
        halfedgeOf[h.directed()] = std::uint32_t(m.halfedge_handle(sharedEdge, h.direction()).idx());
      } else {  // halfedge 0 runs the refused triangle's way between its copies
        const OpenMesh::EdgeHandle e(edge++);
        m.set_vertex_handle(m.halfedge_handle(e, 0), OpenMesh::VertexHandle(int(copyOf[t] + (h.corner() + 1) % 3)));
        m.set_vertex_handle(m.halfedge_handle(e, 1), OpenMesh::VertexHandle(int(copyOf[t] + h.corner())));
        halfedgeOf[h.directed()] = std::uint32_t(m.halfedge_handle(e, 0).idx());
      }
    }
  }
  out.edgeGroups.push_back(std::uint32_t(edge));
}

// Faces: the kept triangles in order, then the refused ones (as OpenMesh's importer adds them).
void linkFaces(HalfEdgeMesh& out, const std::vector<glm::uvec3>& tris, const std::vector<std::uint8_t>& kept,
               const std::vector<std::uint32_t>& copyOf, const std::vector<std::uint32_t>& halfedgeOf) {
  SilhouetteTriMesh& m = out.mesh;
  out.triangleOf.reserve(m.n_faces());
  const auto addFace = [&](std::uint32_t t) {
    const OpenMesh::FaceHandle f(int(out.triangleOf.size()));
    const auto halfedge = [&](std::uint32_t k) { return OpenMesh::HalfedgeHandle(int(halfedgeOf[3 * t + k])); };
    out.faceOf[t] = f.idx();
    out.triangleOf.push_back(t);
    m.set_halfedge_handle(f, halfedge(0));
    for (std::uint32_t k = 0; k < 3; ++k) {
      const OpenMesh::HalfedgeHandle h = halfedge(k);
      m.set_face_handle(h, f);
      m.set_next_halfedge_handle(h, halfedge((k + 1) % 3));
      m.set_halfedge_handle(OpenMesh::VertexHandle(int(copyOf[t] == kNone ? tris[t][k] : copyOf[t] + k)), h);
    }
  };
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    if (kept[t]) addFace(t);
  for (std::uint32_t t : out.refused) addFace(t);
}

// Boundary halfedges: each open fan at a vertex has one arriving (x -> v) and one leaving
// (v -> y); the arriving one of fan i continues with the leaving one of fan i + 1, so that
// circulating the vertex visits every fan, and the vertex keeps a leaving boundary halfedge
// (OpenMesh's conventions for boundary and non-manifold vertices).
void linkBoundaries(HalfEdgeMesh& out) {
  SilhouetteTriMesh& m = out.mesh;
  struct Boundary {
    std::uint32_t vertex;
    int arriving, leaving;
    bool operator<(const Boundary& o) const { return arriving < o.arriving; }  // within a vertex's bucket
  };
  std::vector<Boundary> boundary;
  const int halfedgeCount = int(m.n_halfedges());
  for (int i = 0; i < halfedgeCount; ++i) {
    const OpenMesh::HalfedgeHandle in(i);
    if (m.face_handle(in).is_valid()) continue;
    OpenMesh::HalfedgeHandle h = m.opposite_halfedge_handle(in);
    for (int steps = 0;; ++steps) {
      PENUMBRA_CHECK(steps < halfedgeCount, "buildHalfEdgeMesh: a fan without an end");
      const OpenMesh::HalfedgeHandle o = m.opposite_halfedge_handle(m.prev_halfedge_handle(h));
      h = o;
      if (!m.face_handle(o).is_valid()) break;
    }
    boundary.push_back({std::uint32_t(m.to_vertex_handle(in).idx()), i, h.idx()});
  }
  boundary = bucketSort(boundary, out.weldedOf.size(), [](const Boundary& b) { return b.vertex; });
  for (std::size_t i = 0, j = 0; i < boundary.size(); i = j) {
    for (j = i; j < boundary.size() && boundary[j].vertex == boundary[i].vertex;) ++j;
    for (std::size_t k = i; k < j; ++k)
      m.set_next_halfedge_handle(OpenMesh::HalfedgeHandle(boundary[k].arriving),
                                 OpenMesh::HalfedgeHandle(boundary[k + 1 < j ? k + 1 : i].leaving));
    m.set_halfedge_handle(OpenMesh::VertexHandle(int(boundary[i].vertex)),
                          OpenMesh::HalfedgeHandle(boundary[i].leaving));
  }
}

}  // namespace

OpenMesh::HalfedgeHandle HalfEdgeMesh::cornerHalfedge(OpenMesh::FaceHandle f, const glm::uvec3& tri, int corner) const {
  OpenMesh::HalfedgeHandle h = mesh.halfedge_handle(f);
  for (int i = 0; i < 3 && welded(mesh.from_vertex_handle(h)) != tri[corner]; ++i) h = mesh.next_halfedge_handle(h);
  return h;
}

// Which triangles are kept (complex edges, then complex vertices refused, as add_face would),
// then the OpenMesh arrays linked in bulk: vertices, edges, faces, boundaries.
std::shared_ptr<HalfEdgeMesh> buildHalfEdgeMesh(const std::vector<glm::vec3>& weldedPositions,
                                                const std::vector<glm::uvec3>& tris) {
  const std::size_t vertexCount = weldedPositions.size(), triangleCount = tris.size();
  PENUMBRA_CHECK(triangleCount < (std::size_t(1) << 31) / 3, "buildHalfEdgeMesh: more than 715 million triangles");
  EdgeGroups groups = groupEdges(vertexCount, tris);
  Kept kept = keepManifoldEdges(groups, tris);
  refuseComplexVertices(vertexCount, tris, kept);

  // Built in place: OpenMesh's kernel has no move constructor, so moving a HalfEdgeMesh would
  // copy the whole mesh.
  const auto built = std::make_shared<HalfEdgeMesh>();
  HalfEdgeMesh& out = *built;
  out.weldedCount = vertexCount;
  out.faceOf.assign(triangleCount, -1);
  const std::vector<std::uint32_t> copyOf = copyRefused(out, tris, kept.triangle);
  const std::size_t faceCount = triangleCount - std::size_t(std::count_if(tris.begin(), tris.end(), collapsed));
  SilhouetteTriMesh& m = out.mesh;
  m.resize(out.weldedOf.size(), edgeCount(groups, kept.triangle), faceCount);
  std::vector<OpenMesh::Vec3d>& points = m.property(m.points_pph()).data_vector();
  for (std::size_t v = 0; v < out.weldedOf.size(); ++v) points[v] = toOpenMesh(weldedPositions[out.weldedOf[v]]);
  // Directed edge -> OpenMesh halfedge, in the memory of groupOf (no longer needed).
  std::vector<std::uint32_t> halfedgeOf = std::move(groups.groupOf);
  linkEdges(out, groups, kept.triangle, copyOf, halfedgeOf);
  linkFaces(out, tris, kept.triangle, copyOf, halfedgeOf);
  linkBoundaries(out);
  return built;
}

std::vector<glm::vec3> cornerNormals(const EdgeTopology& topology, double creaseAngle) {
  PENUMBRA_CHECK(topology.halfEdges != nullptr, "cornerNormals needs a topology from buildEdgeTopology");
  const HalfEdgeMesh& hem = *topology.halfEdges;
  const SilhouetteTriMesh& m = hem.mesh;
  const std::size_t triangles = topology.weldedTriangles.size();
  std::vector<glm::dvec3> unit(triangles, glm::dvec3(0.0));
  for (std::size_t t = 0; t < triangles; ++t) {
    const double len = glm::length(topology.faceNormals[t]);
    if (len > 0.0) unit[t] = topology.faceNormals[t] / len;
  }
  const bool smoothAll = creaseAngle >= 3.14159265358979323846;
  const double cosCrease = std::cos(std::max(creaseAngle, 0.0));
  const auto triangleOf = [&](OpenMesh::FaceHandle f) { return hem.triangleOf[std::size_t(f.idx())]; };
  // Across an edge between faces a and b: smooth when both have an area and their normals are
  // within the crease angle.
  const auto smooth = [&](OpenMesh::FaceHandle a, OpenMesh::FaceHandle b) {
    const glm::dvec3 &na = unit[triangleOf(a)], &nb = unit[triangleOf(b)];
    if (glm::dot(na, na) == 0.0 || glm::dot(nb, nb) == 0.0) return false;
    return smoothAll || glm::dot(na, nb) >= cosCrease;
  };
  // The face's unit normal weighted by its angle at the vertex `in` points to (Thürmer and
  // Wüthrich 1998, "Computing vertex normals from polygonal facets").
  const auto weighted = [&](OpenMesh::HalfedgeHandle in) {
    const glm::dvec3 v = toGlm(m.point(m.to_vertex_handle(in)));
    const glm::dvec3 a = toGlm(m.point(m.from_vertex_handle(in))) - v;
    const glm::dvec3 b = toGlm(m.point(m.to_vertex_handle(m.next_halfedge_handle(in)))) - v;
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * unit[triangleOf(m.face_handle(in))];
  };

  std::vector<glm::vec3> out(3 * triangles, glm::vec3(0.0f));
  for (std::size_t t = 0; t < triangles; ++t) {
    const OpenMesh::FaceHandle f(hem.faceOf[t]);
    if (!f.is_valid()) continue;  // collapsed under welding: no area, no normal
    for (int c = 0; c < 3; ++c) {
      const OpenMesh::HalfedgeHandle in = m.prev_halfedge_handle(hem.cornerHalfedge(f, topology.weldedTriangles[t], c));
      glm::dvec3 sum = weighted(in);
      // One way round the vertex: the face across the edge leaving it (next of `in`) ...
      bool fullCircle = false;
      for (OpenMesh::HalfedgeHandle g = in;;) {
        const OpenMesh::HalfedgeHandle o = m.opposite_halfedge_handle(m.next_halfedge_handle(g));
        const OpenMesh::FaceHandle nf = m.face_handle(o);
        if (!nf.is_valid() || !smooth(m.face_handle(g), nf)) break;
        if (nf == f) {
          fullCircle = true;
          break;
        }
        sum += weighted(o);
        g = o;
      }
      // ... and the other way, across the edge arriving at it, up to a crease or a boundary.
      for (OpenMesh::HalfedgeHandle g = in; !fullCircle;) {
        const OpenMesh::HalfedgeHandle o = m.opposite_halfedge_handle(g);
        const OpenMesh::FaceHandle nf = m.face_handle(o);
        if (!nf.is_valid() || nf == f || !smooth(m.face_handle(g), nf)) break;
        g = m.prev_halfedge_handle(o);
        sum += weighted(g);
      }
      const double len = glm::length(sum);
      out[3 * t + std::size_t(c)] = glm::vec3(len > 0.0 ? sum / len : unit[t]);
    }
  }
  return out;
}

}  // namespace penumbra::geo
