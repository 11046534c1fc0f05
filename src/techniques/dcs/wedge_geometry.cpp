#include "techniques/dcs/wedge_geometry.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra::dcs {

glm::vec4 trianglePlane(const std::vector<glm::vec3>& P, const glm::uvec3& tri) {
  glm::dvec3 a(P[tri.x]), b(P[tri.y]), c(P[tri.z]);
  glm::dvec3 n = glm::cross(b - a, c - a);
  return glm::vec4(glm::vec3(n), float(-glm::dot(n, a)));
}

bool EdgeTable::useRules(const std::vector<geo::VolumeRule>& meshRules) {
  if (meshRules == rules) return false;
  for (std::size_t mi = 0; mi < meshRules.size(); ++mi) {
    const std::size_t end = mi + 1 < offset.size() ? offset[mi + 1] : edges.size();
    for (std::size_t e = offset[mi]; e < end; ++e)
      edges[e].meta.z = meshRules[mi] == geo::VolumeRule::ClosedFrontFaces ? 1 : 0;
  }
  rules = meshRules;
  return true;
}

std::size_t EdgeTable::bandOf(std::uint32_t e) const {
  const auto it = std::upper_bound(bands.begin(), bands.end(), e,
                                   [](std::uint32_t id, const EdgeBand& b) { return id < b.firstEdge; });
  PENUMBRA_CHECK(it != bands.begin() && e < std::prev(it)->endEdge, "dcs: edge outside the table's bands");
  return std::size_t(std::prev(it) - bands.begin());
}

EdgeTable buildEdgeTable(const std::vector<ShadowVolumeCounter::MeshVolumes>& meshes, std::size_t bandBytes) {
  EdgeTable t;
  for (auto& m : meshes) {
    t.offset.push_back(std::uint32_t(t.edges.size()));
    t.rules.push_back(m.rule);
    const auto& topo = m.topology;
    const auto& P = topo.weldedPositions;
    for (auto& e : topo.edges) {
      t.edges.push_back({glm::vec4(P[e.v0], 1.0f), glm::vec4(P[e.v1], 1.0f),
                         glm::ivec4(int(t.incidences.size()), int(e.incidenceCount),
                                    m.rule == geo::VolumeRule::ClosedFrontFaces ? 1 : 0, m.units)});
      for (std::uint32_t k = 0; k < e.incidenceCount; ++k) {
        const auto& inc = topo.incidences[e.firstIncidence + k];
        const glm::uvec3& tri = topo.weldedTriangles[inc.triangle];
        std::uint32_t third = tri.x + tri.y + tri.z - e.v0 - e.v1;
        t.incidences.push_back({glm::vec4(P[third], float(inc.orientation)), trianglePlane(P, tri)});
      }
    }
  }
  // Bands, greedily: an edge opens a new band when it or its incidences would pass bandBytes.
  const std::size_t maxEdges = bandBytes ? bandBytes / sizeof(GpuEdge) : t.edges.size(),
                    maxIncidences = bandBytes ? bandBytes / sizeof(GpuIncidence) : t.incidences.size();
  EdgeBand band;
  for (std::uint32_t e = 0; e < std::uint32_t(t.edges.size()); ++e) {
    GpuEdge& edge = t.edges[e];
    const std::uint32_t first = std::uint32_t(edge.meta.x), count = std::uint32_t(edge.meta.y);
    if (count > maxIncidences || maxEdges == 0)
      throw Error("dcs",
                  fmt::format("an edge with {} incident triangles needs {:.3g} MiB, more than a band of "
                              "edges holds ({:.3g} MiB)",
                              count, double(count * sizeof(GpuIncidence)) / 1048576.0, double(bandBytes) / 1048576.0));
    if (e > band.firstEdge && (e - band.firstEdge >= maxEdges || first + count - band.firstIncidence > maxIncidences)) {
      t.bands.push_back(band);
      band = {e, e, first, first};
    }
    edge.meta.x = int(first - band.firstIncidence);
    band.endEdge = e + 1, band.endIncidence = first + count;
  }
  if (!t.edges.empty()) t.bands.push_back(band);
  return t;
}

geo::LightExtent extentOf(const Light& l) {
  geo::LightExtent e;
  e.centre = l.position;
  e.normal = l.normal;
  e.tangent = l.tangent;
  e.bitangent = l.bitangent();
  switch (l.shape) {
    case LightShape::Point:
      e.kind = geo::LightExtent::Kind::Point;
      break;
    case LightShape::Rect:
      e.kind = geo::LightExtent::Kind::Rect;
      e.halfWidth = 0.5 * l.size.x, e.halfHeight = 0.5 * l.size.y;
      break;
    case LightShape::Disk:
      e.kind = geo::LightExtent::Kind::Disk, e.radius = l.size.x;
      break;
    case LightShape::Sphere:
      e.kind = geo::LightExtent::Kind::Sphere, e.radius = l.size.x;
      break;
  }
  return e;
}

std::vector<glm::vec3> lightCorners(const Light& l, float& radius) {
  glm::vec3 c = l.position, t = l.tangent, b = l.bitangent(), n = l.normal;
  std::vector<glm::vec3> out;
  float hx = 0, hy = 0, hz = 0;
  if (l.shape == LightShape::Rect) hx = 0.5f * l.size.x, hy = 0.5f * l.size.y;
  if (l.shape == LightShape::Disk) hx = hy = l.size.x;
  if (l.shape == LightShape::Sphere) hx = hy = hz = l.size.x;
  // Grown by 0.1%: samples on the light's border stay strictly inside the wedges.
  hx *= 1.001f, hy *= 1.001f, hz *= 1.001f;
  radius = l.shape == LightShape::Disk ? l.size.x : std::sqrt(hx * hx + hy * hy + hz * hz);
  // In cyclic order around the light (dcs_wedge.geom clips the polygon).
  for (float sz : {-1.0f, 1.0f}) {
    for (glm::vec2 s : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
      out.push_back(c + s.x * hx * t + s.y * hy * b + sz * hz * n);
    if (hz == 0.0f) break;
  }
  if (l.shape == LightShape::Point) out.assign(1, c);
  return out;
}

}  // namespace penumbra::dcs
