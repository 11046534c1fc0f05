// Mesh cleaning, vertex welding and edge topology. Linear time apart from sorts within one
// vertex's edge fan (and OpenMesh's add_face, linear in a vertex's valence), and keyed only on
// integers and bit patterns, so the results are identical on every run and machine.
#include "geometry/mesh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numeric>
#include <string>
#include <tuple>
#include <utility>

#include "core/error.h"
#include "geometry/bucket_sort.h"
#include "geometry/half_edge_mesh.h"

namespace penumbra::geo {
namespace {

// Exact-position key: -0.0 and 0.0 must weld (mirrored instances produce both), so zero is
// normalised before taking the bits. NaNs keep their bits; their triangles are dropped anyway.
std::uint32_t coordinateBits(float f) { return std::bit_cast<std::uint32_t>(f == 0.0f ? 0.0f : f); }

std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

struct Welding {
  std::vector<std::uint32_t> index;  // input vertex -> welded id, ids in order of first use
  std::vector<std::uint32_t> first;  // welded id -> first input vertex with that position
};

// Open-addressing hash on the bit patterns. Vertices are inserted in input order, so the ids
// do not depend on the hash.
Welding weldPositions(const std::vector<glm::vec3>& positions) {
  const auto bits = [&](std::size_t v) {
    const glm::vec3& p = positions[v];
    return std::array<std::uint32_t, 3>{coordinateBits(p.x), coordinateBits(p.y), coordinateBits(p.z)};
  };
  constexpr std::uint32_t kEmpty = 0xffffffffu;
  const std::size_t capacity = std::bit_ceil(2 * positions.size() + 2);
  std::vector<std::uint32_t> slots(capacity, kEmpty);  // first vertex of each position
  Welding w;
  w.index.resize(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const auto key = bits(v);
    std::size_t slot = mix((std::uint64_t{key[0]} << 32 | key[1]) ^ mix(key[2])) & (capacity - 1);
    while (slots[slot] != kEmpty && bits(slots[slot]) != key) slot = (slot + 1) & (capacity - 1);
    if (slots[slot] == kEmpty) {
      slots[slot] = static_cast<std::uint32_t>(v);
      w.index[v] = static_cast<std::uint32_t>(w.first.size());
      w.first.push_back(static_cast<std::uint32_t>(v));
    } else {
      w.index[v] = w.index[slots[slot]];
    }
  }
  return w;
}

bool isFinite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

bool hasZeroArea(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
  return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
}

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

void appendCount(std::string& out, std::size_t n, const char* what) {
  if (n == 0) return;
  out += ", " + std::to_string(n) + " " + what;
}

// The welded triangles go into an OpenMesh TriMesh (half_edge_mesh.h); the edges are its
// edges grouped by welded end points, so the copies made for refused faces sum with the edges
// they copy, and the face normals are read from each face's halfedges.
EdgeTopology buildTopology(const TriangleMesh& mesh, Welding w) {
  EdgeTopology topo;
  topo.weldedIndex = std::move(w.index);
  topo.weldedPositions.reserve(w.first.size());
  for (std::uint32_t v : w.first) topo.weldedPositions.push_back(mesh.positions[v]);
  topo.weldedTriangles.reserve(mesh.triangles.size());
  for (const glm::uvec3& tri : mesh.triangles) {
    const std::vector<std::uint32_t>& id = topo.weldedIndex;
    PENUMBRA_CHECK(tri.x < id.size() && tri.y < id.size() && tri.z < id.size(),
                   "buildEdgeTopology needs in-range indices (run cleanMesh first)");
    topo.weldedTriangles.emplace_back(id[tri.x], id[tri.y], id[tri.z]);
  }
  std::shared_ptr<const HalfEdgeMesh> halfEdges = buildHalfEdgeMesh(topo.weldedPositions, topo.weldedTriangles);
  const HalfEdgeMesh& hem = *halfEdges;
  const SilhouetteTriMesh& m = hem.mesh;
  topo.duplicatedVertices = hem.duplicatedVertices();

  // cross(edge p0 -> p1, -(edge p2 -> p0)) = cross(p1 - p0, p2 - p0) over the mesh's double
  // points, read at the triangle's welded vertices rather than by walking the face's halfedges
  // (scattered reads): a refused face's copies hold the same points. The second edge is
  // negated as the halfedge walk gave it, so even the signs of zero components are unchanged.
  topo.faceNormals.assign(topo.weldedTriangles.size(), glm::dvec3(0.0));
  const auto point = [&](std::uint32_t v) {
    const OpenMesh::Vec3d& p = m.point(OpenMesh::VertexHandle(int(v)));
    return glm::dvec3(p[0], p[1], p[2]);
  };
  for (std::size_t t = 0; t < topo.weldedTriangles.size(); ++t) {
    if (hem.faceOf[t] < 0) continue;
    const glm::uvec3& tri = topo.weldedTriangles[t];
    const glm::dvec3 p0 = point(tri.x);
    topo.faceNormals[t] = glm::cross(point(tri.y) - p0, -(p0 - point(tri.z)));
  }

  // Welded edge g is the OpenMesh edges of group g; its incidences are their halfedges' faces.
  const std::size_t groups = hem.edgeGroups.empty() ? 0 : hem.edgeGroups.size() - 1;
  topo.edges.reserve(groups);
  topo.incidences.reserve(2 * m.n_edges());
  bool closed = groups > 0;
  for (std::size_t g = 0; g < groups; ++g) {
    const auto first = static_cast<std::uint32_t>(topo.incidences.size());
    int orientationSum = 0;
    for (std::uint32_t e = hem.edgeGroups[g]; e < hem.edgeGroups[g + 1]; ++e) {
      for (int side = 0; side < 2; ++side) {
        const OpenMesh::HalfedgeHandle h = m.halfedge_handle(OpenMesh::EdgeHandle(int(e)), side);
        const OpenMesh::FaceHandle f = m.face_handle(h);
        if (!f.is_valid()) continue;  // the boundary side
        const std::int8_t orientation =
            hem.welded(m.from_vertex_handle(h)) < hem.welded(m.to_vertex_handle(h)) ? 1 : -1;
        topo.incidences.push_back({hem.triangleOf[std::size_t(f.idx())], orientation});
        orientationSum += orientation;
      }
    }
    const auto count = static_cast<std::uint32_t>(topo.incidences.size() - first);
    const auto before = [](const EdgeTopology::Incidence& a, const EdgeTopology::Incidence& b) {
      return std::tie(a.triangle, a.orientation) < std::tie(b.triangle, b.orientation);
    };
    if (count == 2 && before(topo.incidences[first + 1], topo.incidences[first]))
      std::swap(topo.incidences[first], topo.incidences[first + 1]);
    else if (count > 2)
      std::sort(topo.incidences.begin() + first, topo.incidences.end(), before);
    const OpenMesh::HalfedgeHandle h = m.halfedge_handle(OpenMesh::EdgeHandle(int(hem.edgeGroups[g])), 0);
    const std::uint32_t a = hem.welded(m.from_vertex_handle(h)), b = hem.welded(m.to_vertex_handle(h));
    topo.edges.push_back({std::min(a, b), std::max(a, b), first, count});
    closed = closed && count == 2 && orientationSum == 0;
  }
  topo.closed = closed;
  topo.halfEdges = std::move(halfEdges);
  return topo;
}

}  // namespace

EdgeTopology buildEdgeTopology(const TriangleMesh& mesh) { return buildTopology(mesh, weldPositions(mesh.positions)); }

void cleanMesh(TriangleMesh& mesh, MeshReport& report) {
  if (report.inputVertices == 0 && report.inputFaces == 0) {
    report.inputVertices = mesh.positions.size();
    report.inputFaces = mesh.triangles.size();
  }
  const std::size_t vertexCount = mesh.positions.size();
  const std::vector<glm::vec3>& p = mesh.positions;

  // Per-triangle checks; each dropped triangle is counted under its first failing reason.
  std::vector<std::uint8_t> keep(mesh.triangles.size(), 0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    if (tri.x >= vertexCount || tri.y >= vertexCount || tri.z >= vertexCount) {
      ++report.droppedInvalidIndex;
    } else if (!isFinite(p[tri.x]) || !isFinite(p[tri.y]) || !isFinite(p[tri.z])) {
      ++report.droppedNonFinite;
    } else if (tri.x == tri.y || tri.y == tri.z || tri.z == tri.x || hasZeroArea(p[tri.x], p[tri.y], p[tri.z])) {
      ++report.droppedDegenerate;
    } else {
      keep[t] = 1;
    }
  }

  // Duplicates: same welded vertex set as an earlier kept triangle, in any order or winding.
  // Doubled faces would otherwise turn into non-manifold edges and double shadow counts.
  Welding w = weldPositions(mesh.positions);
  std::vector<std::array<std::uint32_t, 4>> keys;  // sorted welded ids, triangle
  keys.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!keep[t]) continue;
    std::array<std::uint32_t, 3> v = {w.index[mesh.triangles[t].x], w.index[mesh.triangles[t].y],
                                      w.index[mesh.triangles[t].z]};
    std::sort(v.begin(), v.end());
    keys.push_back({v[0], v[1], v[2], static_cast<std::uint32_t>(t)});
  }
  keys = bucketSort(keys, w.first.size(), [](const auto& k) { return k[0]; });
  for (std::size_t i = 1; i < keys.size(); ++i) {
    if (keys[i][0] == keys[i - 1][0] && keys[i][1] == keys[i - 1][1] && keys[i][2] == keys[i - 1][2]) {
      keep[keys[i][3]] = 0;
      ++report.droppedDuplicate;
    }
  }

  std::size_t kept = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (keep[t]) mesh.triangles[kept++] = mesh.triangles[t];
  }
  mesh.triangles.resize(kept);
  report.triangles = kept;

  // Huge magnitudes are kept (a world may be large) but lose float precision in the volumes.
  std::vector<std::uint8_t> used(vertexCount, 0);
  for (const glm::uvec3& tri : mesh.triangles) used[tri.x] = used[tri.y] = used[tri.z] = 1;
  report.hugeCoordinates = 0;
  for (std::size_t v = 0; v < vertexCount; ++v) {
    if (used[v] && glm::max(glm::abs(p[v].x), glm::max(glm::abs(p[v].y), glm::abs(p[v].z))) > 1e6f)
      ++report.hugeCoordinates;
  }

  const EdgeTopology topo = buildTopology(mesh, std::move(w));
  report.openEdges = report.nonManifoldEdges = report.inconsistentEdges = 0;
  std::vector<std::uint32_t> parent(mesh.triangles.size());
  std::iota(parent.begin(), parent.end(), 0u);
  for (const EdgeTopology::Edge& e : topo.edges) {
    if (e.incidenceCount == 1) ++report.openEdges;
    if (e.incidenceCount > 2) ++report.nonManifoldEdges;
    if (e.incidenceCount == 2 &&
        topo.incidences[e.firstIncidence].orientation == topo.incidences[e.firstIncidence + 1].orientation)
      ++report.inconsistentEdges;
    const std::uint32_t root = findRoot(parent, topo.incidences[e.firstIncidence].triangle);
    for (std::uint32_t k = 1; k < e.incidenceCount; ++k)
      parent[findRoot(parent, topo.incidences[e.firstIncidence + k].triangle)] = root;
  }
  report.components = 0;
  for (std::uint32_t t = 0; t < parent.size(); ++t) {
    if (findRoot(parent, t) == t) ++report.components;
  }
  report.closed = topo.closed;
  report.duplicatedVertices = topo.duplicatedVertices;
}

std::string MeshReport::summary() const {
  std::string s = std::to_string(triangles) + (triangles == 1 ? " triangle" : " triangles");
  s += ", " + std::to_string(droppedTotal()) + " dropped";
  if (droppedTotal() > 0) {
    std::string parts;
    appendCount(parts, droppedInvalidIndex, "invalid index");
    appendCount(parts, droppedDegenerate, "degenerate");
    appendCount(parts, droppedNonFinite, "non-finite");
    appendCount(parts, droppedDuplicate, "duplicate");
    s += " (" + parts.substr(2) + ")";
  }
  appendCount(s, polygonsTriangulated, "polygons triangulated");
  appendCount(s, duplicatedVertices, "vertices duplicated for refused faces");
  appendCount(s, hugeCoordinates, "vertices with |coordinate| > 1e6");
  appendCount(s, ignoredElements, "line/point elements ignored");
  if (vertexColours) s += ", vertex colours not used";
  appendCount(s, openEdges, "open edges");
  appendCount(s, nonManifoldEdges, "non-manifold edges");
  appendCount(s, inconsistentEdges, "inconsistently wound edges");
  appendCount(s, components, components == 1 ? "component" : "components");
  s += closed ? ", closed" : ", not closed";
  return s;
}

void ensureShadingNormals(TriangleMesh& mesh, double creaseAngle) {
  if (!mesh.normals.empty() && mesh.normals.size() == mesh.positions.size()) return;
  const std::vector<glm::vec3> corner = cornerNormals(buildEdgeTopology(mesh), creaseAngle);
  constexpr std::uint32_t kNone = 0xffffffffu;
  const bool hasUv = mesh.uvs.size() == mesh.positions.size();
  const std::size_t original = mesh.positions.size();
  mesh.normals.assign(original, glm::vec3(0.0f));
  std::vector<std::uint8_t> assigned(original, 0);
  std::vector<std::uint32_t> nextCopy(original, kNone);  // vertex -> its next copy (a list per original)
  const auto same = [](const glm::vec3& a, const glm::vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      std::uint32_t& index = mesh.triangles[t][k];
      const glm::vec3& n = corner[3 * t + std::size_t(k)];
      if (!assigned[index]) {
        assigned[index] = 1;
        mesh.normals[index] = n;
        continue;
      }
      std::uint32_t v = index, last = index;
      while (v != kNone && !same(mesh.normals[v], n)) last = v, v = nextCopy[v];
      if (v == kNone) {  // a new normal at this position: a copy of the vertex
        v = std::uint32_t(mesh.positions.size());
        const glm::vec3 p = mesh.positions[index];
        mesh.positions.push_back(p);
        if (hasUv) {
          const glm::vec2 uv = mesh.uvs[index];
          mesh.uvs.push_back(uv);
        }
        mesh.normals.push_back(n);
        nextCopy.push_back(kNone);
        nextCopy[last] = v;
      }
      index = v;
    }
  }
}

}  // namespace penumbra::geo
