#include "techniques/dcs/gpu_silhouette.h"

#include <algorithm>

#include <glm/glm.hpp>

#include "techniques/dcs/shaders/dcs_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra::dcs {

std::vector<int> gpuAccurateSilhouette(const gl::Program& p, const gl::Buffer& edges, const gl::Buffer& incidences,
                                       std::uint32_t total, const geo::LightExtent& l) {
  gl::Buffer out(sizeof(std::uint32_t) * (1 + std::size_t(total)), nullptr);
  std::uint32_t zero = 0;
  out.write(&zero, sizeof zero);
  edges.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_EDGES);
  incidences.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_INCIDENCES);
  out.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_STATUS);
  p.use();
  p.set("totalEdges", total);
  p.set("lightKind", int(l.kind));
  p.set("lightCentre", glm::vec3(l.centre));
  p.set("lightNormal", glm::vec3(l.normal));
  p.set("lightTangent", glm::vec3(l.tangent));
  p.set("lightBitangent", glm::vec3(l.bitangent));
  p.set("lightHalfSize", glm::vec2(float(l.halfWidth), float(l.halfHeight)));
  p.set("lightRadius", float(l.radius));
  glDispatchCompute((total + 63) / 64, 1, 1);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  std::uint32_t count = 0;
  out.read(&count, sizeof count);
  std::vector<std::uint32_t> ids(count);
  if (count) out.read(ids.data(), sizeof(std::uint32_t) * count, sizeof(std::uint32_t));
  std::sort(ids.begin(), ids.end());
  return std::vector<int>(ids.begin(), ids.end());
}

}  // namespace penumbra::dcs
