// What dcs's wedge passes read about the scene and the light: every mesh's edges with their
// incident triangles, in the std430 layouts of src/techniques/dcs/shaders/common_dcs.glsl, in
// bands of at most one storage block each (a scene of any size), and the convex polytope around
// the light that each edge's wedge solid spans (dcs_wedge.geom).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/silhouette.h"
#include "scene/scene.h"
#include "techniques/common/shadow_volume/shadow_volume.h"

namespace penumbra::dcs {

struct GpuEdge {
  glm::vec4 v0, v1;
  glm::ivec4 meta;  // first incidence, incidence count, closed rule, units of the mesh
};
struct GpuIncidence {
  glm::vec4 third;   // xyz third vertex, w the triangle's orientation along the edge (+-1)
  glm::vec4 normal;  // the triangle's plane: n (its winding), w = d with n . x + d = 0
};
// A triangle the path from the light centre to a sample passes through (src/techniques/dcs/shaders/dcs_init.frag).
struct GpuPathCrossing {
  glm::vec4 plane;  // the triangle's plane as in GpuIncidence::normal
  glm::ivec4 meta;  // x the centre's side, y the sample's side (+-1, 0 on it), z 1 for the closed rule, w units
};

// The triangle's plane n . x + d = 0 in its own winding, as the wedges store it (one expression,
// so the init pass and the wedges decide a point's side of it alike).
glm::vec4 trianglePlane(const std::vector<glm::vec3>& P, const glm::uvec3& tri);

// A run of the table's edges, [firstEdge, endEdge), and their incidences, [firstIncidence,
// endIncidence): one storage block each, bound on their own, the wedge passes run once per band
// with band-relative edge ids. An edge's first incidence (meta.x) counts from its band's.
struct EdgeBand {
  std::uint32_t firstEdge = 0, endEdge = 0, firstIncidence = 0, endIncidence = 0;
};

// All meshes' edges and incident triangles, edge ids global (a mesh's edges are
// [offset[m], offset[m + 1])), in bands. The units of the mesh ride with each edge: an update is
// m_e(p) times them.
struct EdgeTable {
  std::vector<GpuEdge> edges;
  std::vector<GpuIncidence> incidences;
  std::vector<std::uint32_t> offset;   // mesh -> its first edge
  std::vector<geo::VolumeRule> rules;  // per mesh, the rule its edges' closed flag (meta.z) says
  std::vector<EdgeBand> bands;         // in order, covering every edge (none without edges)

  // The band holding edge `e`.
  std::size_t bandOf(std::uint32_t e) const;

  // Sets each edge's closed flag as `rules` (one per mesh) says; returns whether one changed.
  bool useRules(const std::vector<geo::VolumeRule>& meshRules);
};

// The table of `meshes`, its edges and incidences split into bands of at most `bandBytes` each
// (0: one band), as vwss splits its points: a scene whose edges pass one storage block
// (GL_MAX_SHADER_STORAGE_BLOCK_SIZE, llvmpipe 128 MiB: 2.8 M edges) renders in several bands with
// the same counts. An edge whose own incidences pass `bandBytes` (a non-manifold edge shared by
// millions of triangles) is a one-line refusal naming dcs.
EdgeTable buildEdgeTable(const std::vector<ShadowVolumeCounter::MeshVolumes>& meshes, std::size_t bandBytes);

// The light as the CPU silhouette tests see it (geometry/silhouette.h).
geo::LightExtent extentOf(const Light& l);

// Corners of a convex polytope around the light (for the wedges), in cyclic order per face, and
// its bounding radius around the centre.
std::vector<glm::vec3> lightCorners(const Light& l, float& radius);

}  // namespace penumbra::dcs
