// `hard-sv`: hard shadows from the light centre with z-fail shadow volumes (Everitt & Kilgard,
// "Practical and robust stenciled shadow volumes", 2002), counted in a float target (DCS paper
// 7.2: one pass, additive blending, no 8-bit stencil wrap-around).
//
// Volumes: geometry/silhouette.h gives, per mesh and light, the side edges with multiplicity
// m_e and the cap sign of each triangle (closed meshes: classic front-face caps; open,
// non-manifold or inconsistently wound meshes: one volume per triangle, so boundary edges close
// the volume and the count does not depend on winding). The geometry shader extrudes them to
// infinity. Depth test: a volume fragment counts if it lies behind the visible surface. The
// visible surface's own near cap coincides with it; we push volume fragments back by a
// polygon offset so coincident caps always count, which gives the winding number on the
// camera's side of the surface (the lit side whenever the horizon rule passes).
#include "techniques/hard_sv/hard_sv.h"

#include "geometry/silhouette.h"
#include "core/log.h"
#include "gl/objects.h"
#include "pipeline/renderer.h"
#include "sampling/shared.hpp"

namespace penumbra {
namespace {

class HardShadowVolumes final : public Technique {
 public:
  void prepare(const Scene& scene, GpuScene& gpu) override {
    if (scene.hasSemiOpaque())
      PLOG_WARN("hard-sv treats semi-opaque occluders as opaque (its error against the reference says how much)");
    meshes_.clear();
    for (auto& m : scene.meshes) {
      MeshVolumes v;
      v.topology = geo::buildEdgeTopology(m.mesh);
      v.rule = geo::volumeRuleFor(v.topology);
      meshes_.push_back(std::move(v));
    }
    sides_ = gl::Program({"hardsv_volume.vert", "hardsv_volume.geom", "hardsv_volume.frag"}, {"SIDES"});
    caps_ = gl::Program({"hardsv_volume.vert", "hardsv_volume.geom", "hardsv_volume.frag"}, {"CAPS"});
    resolve_ = gl::Program({"fullscreen.vert", "pipeline_resolve.frag"}, {"COUNTER"});
    counter_ = gl::Texture::make2D(GL_R32F, gpu.width(), gpu.height());
    fbo_ = gl::Framebuffer({&counter_}, &gpu.depth());
  }

  void renderVisibility(LightPass& pass) override {
    glm::dvec3 light(pass.light.position);
    std::vector<glm::vec4> sideVerts, capVerts;
    pass.timer.time("silhouettes", [&] {
      for (auto& m : meshes_) {
        auto sil = geo::extractPointSilhouette(m.topology, light, m.rule);
        const auto& P = m.topology.weldedPositions;
        for (auto& s : sil.sides) {
          const auto& e = m.topology.edges[s.edge];
          // m > 0: the effective near cap runs v0 -> v1, so the outward side quad runs v1 -> v0
          // (the shader emits b, a, a_inf, b_inf for input (a, b)).
          glm::vec3 a = P[e.v0], b = P[e.v1];
          if (s.multiplicity < 0) std::swap(a, b);
          float w = float(std::abs(s.multiplicity));
          sideVerts.emplace_back(a, w);
          sideVerts.emplace_back(b, w);
        }
        for (std::size_t t = 0; t < sil.capSign.size(); ++t) {
          if (sil.capSign[t] == 0) continue;
          const auto& tri = m.topology.weldedTriangles[t];
          // c_t = -1 (back-facing triangle of an open mesh): reverse it so the cap faces the light.
          glm::uvec3 o = sil.capSign[t] > 0 ? tri : glm::uvec3(tri.x, tri.z, tri.y);
          capVerts.emplace_back(P[o.x], 1.0f);
          capVerts.emplace_back(P[o.y], 1.0f);
          capVerts.emplace_back(P[o.z], 1.0f);
        }
      }
    });
    stats_.sideEdges = sideVerts.size() / 2;
    stats_.caps = capVerts.size() / 3;

    pass.timer.time("shadow volume", [&] {
      gl::Buffer sideBuf(sideVerts), capBuf(capVerts);
      fbo_.bind();
      const float zero[4] = {0, 0, 0, 0};
      glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, zero);
      glEnable(GL_DEPTH_TEST);
      glDepthMask(GL_FALSE);
      glDepthFunc(GL_LESS);  // reversed Z: smaller depth = farther = behind the surface
      glEnable(GL_DEPTH_CLAMP);
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(-1.0f, -4.0f);  // push volumes back so coincident caps count
      glDisable(GL_CULL_FACE);
      glEnable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      glBlendFunc(GL_ONE, GL_ONE);
      for (auto* prog : {&sides_, &caps_}) {
        prog->use();
        prog->set("clipFromWorld", pass.gpu.clipFromWorld());
        prog->set("lightPosition", pass.light.position);
      }
      drawPoints(sides_, sideBuf, sideVerts.size(), GL_LINES);
      drawPoints(caps_, capBuf, capVerts.size(), GL_TRIANGLES);
      glDisable(GL_BLEND);
      glDisable(GL_POLYGON_OFFSET_FILL);
      glDisable(GL_DEPTH_CLAMP);
      glDisable(GL_DEPTH_TEST);
      glDepthMask(GL_TRUE);
    });

    pass.timer.time("resolve", [&] {
      counter_.bind(PENUMBRA_UNIT_COUNTER);
      resolveVisibility(pass, resolve_);
    });
  }

  std::size_t memoryBytes() const override { return counter_.bytes(); }

 private:
  struct MeshVolumes {
    geo::EdgeTopology topology;
    geo::VolumeRule rule;
  };
  struct Stats {
    std::size_t sideEdges = 0, caps = 0;
  };

  void drawPoints(const gl::Program& prog, const gl::Buffer& buf, std::size_t count, GLenum mode) {
    if (count == 0) return;
    gl::VertexArray vao;
    vao.vertexBuffer(buf, sizeof(glm::vec4)).attribute(0, 4, 0);
    vao.bind();
    prog.use();
    glDrawArrays(mode, 0, GLsizei(count));
  }

  std::vector<MeshVolumes> meshes_;
  gl::Program sides_, caps_, resolve_;
  gl::Texture counter_;
  gl::Framebuffer fbo_;
  Stats stats_;
};

}  // namespace

std::unique_ptr<Technique> makeHardShadowVolumes() { return std::make_unique<HardShadowVolumes>(); }

}  // namespace penumbra
