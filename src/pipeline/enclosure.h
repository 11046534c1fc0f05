// Lights that a closed opaque mesh separates from everything the camera sees.
//
// A closed mesh (every edge shared by two oppositely wound triangles) divides space into cells of
// equal winding number; a path between two cells crosses the surface. So when every light sample
// lies in another cell of a closed, opaque mesh than the camera, and no part of the mesh comes
// nearer the eye than the near plane's corners (the view rays start in the eye's cell), no
// sample reaches any pixel: the light's sampled visibility is 0 everywhere, exactly.
//
// The map techniques see the occluders only from the light centre (one map: pcss, vssm, msm,
// evsm) or rebuild the samples' views from the centre's (vwss, reproject): from there they see
// one side of such a mesh, and light leaked through its walls (a camera in a closed box lit from
// outside: vssm visibility RMSE 0.47; a light in a closed box: vwss and reproject 0.13-0.25, hard
// case 35). They cull such a light (Technique::cullsSeparatedLights), as engines cull lights by
// room; the exact techniques and the references do not (their counts and rays are checked
// against each other on the same scenes). A light with samples in more than one cell of a mesh
// is left to the technique, and named (LightEnclosure::straddled), as the map techniques only
// approximate it.
//
// The windings are geometry/silhouette.h's (locatePoint at the eye and the light centre, the
// sample's from the centre's by the path's crossings, pathCrossings), in double.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "geometry/mesh.h"
#include "sampling/light_samples.h"
#include "scene/scene.h"

namespace penumbra {

struct LightEnclosure {
  std::string separatedBy;              // a closed opaque mesh between every sample and the camera, or empty
  std::string straddled;                // a closed opaque mesh with samples in more than one of its cells, or empty
  std::size_t samplesInOtherCells = 0;  // of `straddled`: samples not in the light centre's cell
};

class Enclosures {
 public:
  // The closed opaque meshes of `scene` and the eye's cell in each; eyeReach: the distance from
  // the eye to the near plane's corners.
  Enclosures(const Scene& scene, double eyeReach);
  // Cached per light index (the renderer's samples of a light do not change).
  const LightEnclosure& classify(int lightIndex, const Light& light, const LightSampleSet& samples);
  std::size_t closedMeshes() const { return closed_.size(); }

 private:
  struct Closed {
    std::string name;
    geo::EdgeTopology topology;
    int eyeWinding = 0;
    bool eyeClear = false;  // the eye not on the surface, no triangle nearer than the near plane's corners
  };
  std::vector<Closed> closed_;
  glm::dvec3 eye_;
  std::map<int, LightEnclosure> cache_;
};

// The distance from the eye to the corners of the near plane of `camera` at `aspect`.
double nearPlaneReach(const Camera& camera, double aspect);

}  // namespace penumbra
