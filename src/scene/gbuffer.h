// The G-buffer on the CPU: per pixel, the surface point the camera sees. The pipeline
// (pipeline/renderer.h) reads it back from the GPU; the Embree reference
// (reference/embree_reference.h) and the shadow-map frustum fits take it as input.
// Scene-level data, GL-free, so that both use it downward.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

namespace penumbra {

// Per-pixel surface data read back from the GPU G-buffer (top row first, like Image).
struct CpuGBuffer {
  int width = 0, height = 0;
  std::vector<glm::vec3> position;  // the scene's coordinates: world position minus `origin`
  std::vector<glm::vec3> normal;    // world, unit, facing the camera
  std::vector<std::uint8_t> valid;  // 1 where a surface was hit
  // The BRDF's inputs (shading/shaders/shading.h penumbraBrdf; empty where a caller gives geometry only):
  std::vector<glm::vec3> shadingNormal;  // unit, on the geometric normal's side
  std::vector<glm::vec3> baseColor;      // linear, the texture applied
  std::vector<glm::vec3> material;       // metallic, roughness, BRDF model (PENUMBRA_BRDF_*)
  std::optional<glm::vec3> camera;       // the view the G-buffer was rendered from, if any
  glm::dvec3 origin{0.0};                // Scene::origin of the scene it was rendered from
};

}  // namespace penumbra
