#include "pipeline/enclosure.h"

#include <algorithm>
#include <cmath>

#include "geometry/silhouette.h"

namespace penumbra {

double nearPlaneReach(const Camera& camera, double aspect) {
  const double t = std::tan(glm::radians(double(camera.fovY)) * 0.5);
  return double(camera.zNear) * std::sqrt(1.0 + t * t * (1.0 + aspect * aspect));
}

Enclosures::Enclosures(const Scene& scene, double eyeReach) : eye_(scene.camera.position) {
  for (const SceneMesh& m : scene.meshes) {
    const Material& mat = scene.materials[std::size_t(m.material)];
    if (mat.opacity != 1.0f || mat.alphaMode != AlphaMode::Opaque || m.mesh.triangles.empty()) continue;
    Closed c;
    c.topology = geo::buildEdgeTopology(m.mesh);
    if (!c.topology.closed) continue;
    c.name = m.name;
    const geo::PointLocation at = geo::locatePoint(c.topology, eye_);
    c.eyeWinding = at.winding;
    c.eyeClear = !at.onSurface && geo::trianglesNearBall(c.topology, eye_, eyeReach).empty();
    closed_.push_back(std::move(c));
  }
}

const LightEnclosure& Enclosures::classify(int lightIndex, const Light& light, const LightSampleSet& samples) {
  auto it = cache_.find(lightIndex);
  if (it != cache_.end()) return it->second;
  LightEnclosure out;
  const glm::dvec3 centre(light.position);
  double reach = 0.0;
  for (const glm::vec3& s : samples.positions) reach = std::max(reach, glm::length(glm::dvec3(s) - centre));
  std::vector<geo::PathCrossing> crossings;
  for (const Closed& c : closed_) {
    const geo::PointLocation at = geo::locatePoint(c.topology, centre);
    // Each sample's winding from the centre's along its path (geo::windingAtPathEnd); a sample
    // on the surface has no cell.
    const std::vector<std::uint32_t> near = geo::trianglesNearBall(c.topology, centre, reach);
    bool onSurface = at.onSurface, apart = c.eyeClear && !at.onSurface;
    std::size_t otherCells = 0;
    for (const glm::vec3& s : samples.positions) {
      crossings.clear();
      if (!near.empty()) geo::pathCrossings(c.topology, near, centre, glm::dvec3(s), crossings);
      const std::optional<int> w = geo::windingAtPathEnd(at.winding, crossings);
      onSurface = onSurface || !w;
      if (!w) break;
      otherCells += *w != at.winding;
      apart = apart && *w != c.eyeWinding;
    }
    if (onSurface) continue;  // touching its surface: neither separated nor straddling
    if (apart && out.separatedBy.empty()) out.separatedBy = c.name;
    if (otherCells > 0 && out.straddled.empty()) {
      out.straddled = c.name;
      out.samplesInOtherCells = otherCells;
    }
  }
  return cache_.emplace(lightIndex, std::move(out)).first->second;
}

}  // namespace penumbra
