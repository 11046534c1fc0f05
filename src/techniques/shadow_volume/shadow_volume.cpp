#include "techniques/shadow_volume/shadow_volume.h"

#include "core/error.h"
#include "pipeline/renderer.h"
#include "sampling/shared.hpp"

namespace penumbra {
namespace {

void drawPoints(const gl::Program& prog, const gl::Buffer& buf, std::size_t count, GLenum mode) {
  if (count == 0) return;
  gl::VertexArray vao = gl::VertexArray::create();
  vao.vertexBuffer(buf, sizeof(glm::vec4)).attribute(0, 4, 0);
  vao.bind();
  prog.use();
  glDrawArrays(mode, 0, GLsizei(count));
}

}  // namespace

void ShadowVolumeCounter::prepare(const Scene& scene, GpuScene& gpu, const std::vector<int>& units, int opaqueUnits) {
  PENUMBRA_CHECK(units.empty() || units.size() == scene.meshes.size(), "ShadowVolumeCounter: one unit count per mesh");
  meshes_.clear();
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    MeshVolumes v;
    v.topology = geo::buildEdgeTopology(scene.meshes[i].mesh);
    v.units = units.empty() ? 1 : units[i];
    v.rule = v.units < opaqueUnits ? geo::VolumeRule::PerTriangle : geo::volumeRuleFor(v.topology);
    meshes_.push_back(std::move(v));
  }
  sidesProgram_ = gl::Program({"hardsv_volume.vert", "hardsv_volume.geom", "hardsv_volume.frag"}, {"SIDES"});
  capsProgram_ = gl::Program({"hardsv_volume.vert", "hardsv_volume.geom", "hardsv_volume.frag"}, {"CAPS"});
  counter_ = gl::Texture::make2D(GL_R32F, gpu.width(), gpu.height());
  fbo_ = gl::Framebuffer({&counter_}, &gpu.depth());
}

void ShadowVolumeCounter::count(LightPass& pass) {
  glm::dvec3 light(pass.light.position);
  std::vector<glm::vec4> sideVerts, capVerts;
  pass.timer.time("silhouettes", [&] {
    for (auto& m : meshes_) {
      if (m.units == 0) continue;
      auto sil = geo::extractPointSilhouette(m.topology, light, m.rule);
      const auto& P = m.topology.weldedPositions;
      for (auto& s : sil.sides) {
        const auto& e = m.topology.edges[s.edge];
        // The edge in its own order, m_e signed (the shader orients the quad): the plane test
        // of the fragment shader must see the same (v0, v1) as dcs's edge buffer.
        float weight = float(s.multiplicity * m.units);
        sideVerts.emplace_back(P[e.v0], weight);
        sideVerts.emplace_back(P[e.v1], weight);
      }
      for (std::size_t t = 0; t < sil.capSign.size(); ++t) {
        if (sil.capSign[t] == 0) continue;
        const auto& tri = m.topology.weldedTriangles[t];
        // c_t = -1 (back-facing triangle of an open mesh): reverse it so the cap faces the light.
        glm::uvec3 o = sil.capSign[t] > 0 ? tri : glm::uvec3(tri.x, tri.z, tri.y);
        capVerts.emplace_back(P[o.x], float(m.units));
        capVerts.emplace_back(P[o.y], float(m.units));
        capVerts.emplace_back(P[o.z], float(m.units));
      }
    }
  });
  sideEdges_ = sideVerts.size() / 2;
  caps_ = capVerts.size() / 3;

  pass.timer.time("shadow volume", [&] {
    gl::Buffer sideBuf(sideVerts), capBuf(capVerts);
    fbo_.bind();
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, zero);
    // No depth test: the fragment shader decides "behind the visible point" by a plane test
    // (hardsv_volume.frag). Depth clamp keeps the parts of the volume in front of the near
    // plane (camera inside a volume).
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_DEPTH_CLAMP);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    for (auto* prog : {&sidesProgram_, &capsProgram_}) {
      prog->use();
      prog->set("clipFromWorld", pass.gpu.clipFromWorld());
      prog->set("lightPosition", pass.light.position);
      prog->set("eyePosition", pass.gpu.cameraPosition());
    }
    drawPoints(sidesProgram_, sideBuf, sideVerts.size(), GL_LINES);
    drawPoints(capsProgram_, capBuf, capVerts.size(), GL_TRIANGLES);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_CLAMP);
  });
}

}  // namespace penumbra
