// The z-fail shadow-volume count from a point (the light centre), shared by `hard-sv` (its
// hard shadow) and `dcs` (the integration constant of the depth complexity, DCS paper 4.1, 7.2).
//
// Z-fail shadow volumes (Everitt & Kilgard, "Practical and robust stenciled shadow volumes",
// 2002), counted by additive blending into an R32F target in one pass (DCS paper 7.2: no 8-bit
// stencil wrap-around). Volumes come from geometry/silhouette.h: per mesh and light, the side
// edges with multiplicity m_e and the cap sign of each triangle (closed meshes: classic
// front-face caps; open, non-manifold or inconsistently wound meshes: one volume per triangle,
// so boundary edges close the volume and the count does not depend on winding). A volume face
// counts where the view ray meets it behind the evaluation point (shared/numerics.h penumbraShadowOrigin:
// the visible point moved towards the camera, off its surface); both halves are decided exactly
// in the fragment shader (shaders/volume_count.h, "Which faces of the shadow volumes the view ray meets";
// src/techniques/common/shadow_volume/shaders/hardsv_volume.frag), not by the rasteriser or the depth buffer: the
// visible surface's own near cap counts, which gives the winding number on the camera's side of the surface (the lit
// side whenever the horizon rule passes), the faces sharing an edge or a vertex line decide it as one (hard case 34),
// and dcs's wedges decide side planes with the same test. The rasteriser draws each face's cover (volume_cover.h),
// built here on the CPU each frame.
#pragma once

#include <string>
#include <vector>

#include "geometry/silhouette.h"
#include "gl/objects.h"
#include "pipeline/technique.h"

namespace penumbra {

// The bytes a band of a scene-sized buffer holds: `requested` (a technique's band-bytes, 0: none)
// within the GL's storage-block limit (GL_MAX_SHADER_STORAGE_BLOCK_SIZE, llvmpipe 128 MiB) and
// 256 MiB (llvmpipe's vertex fetch crashed on a 2.1 GiB vertex buffer: RenderSettings).
std::size_t storageBandBytes(std::size_t requested);
// The smallest band-bytes a technique accepts (a band holds at least one block of faces).
constexpr std::size_t kMinBandBytes = std::size_t(64) << 10;
// The band-bytes parameter of the techniques that size buffers from the scene (hard-sv, dcs), and
// its reading (0 or at least kMinBandBytes).
ParamSpec bandBytesParam();
std::size_t readBandBytes(const TechniqueArgs& args);

class ShadowVolumeCounter {
 public:
  struct MeshVolumes {
    geo::EdgeTopology topology;
    geo::VolumeRule rule;  // for a light outside (place() may give a closed mesh PerTriangle)
    int units = 1;         // what one volume of the mesh adds to the count (0: the mesh never occludes)
    std::string name;
  };

  // Builds the edge topology of every mesh and the GL resources for `gpu`'s size. `units`
  // (empty: 1 for every mesh) weights each mesh's volumes, e.g. by opacity (dcs/opacity.h); a
  // mesh with 0 units is left out, and one with fewer than `opaqueUnits` (semi-opaque) gets
  // one volume per triangle whatever its topology, so the count is the number of surface
  // crossings between the point and the light, as the reference attenuates once per crossing.
  void prepare(const Scene& scene, GpuScene& gpu, const std::vector<int>& units = {}, int opaqueUnits = 1);
  // The most bytes one band of the count's buffers holds (storageBandBytes; 0: the GL's limit).
  void setBandBytes(std::size_t bytes) { bandBytes_ = bytes; }

  // Where a light lies against the meshes (hard cases 27-29), decided on the CPU in double
  // (geometry/silhouette.h locatePoint, pathCrossings). The closed-mesh rule (front-facing caps,
  // the count of closed objects entered) is right for a light point x only when no visible point
  // lies deeper inside the mesh than x: #front - #back = w(p) - w(x) along the segment x -> p,
  // w the winding number, so #front = 0 forces #back = 0 exactly when w(x) <= w(p). Every
  // visible point is seen from the camera, so w(p) = w(eye) (the segment from the eye to p
  // crosses nothing). A closed mesh therefore keeps the closed rule when the centre and every
  // sample lie off its surface with a winding number at most the eye's, and gets one volume per
  // triangle (every crossing counts, right for any point) otherwise: a light centre inside, on a
  // face, an edge or a vertex, samples inside or on it. `crossings[k]` (dcs): the triangles the
  // straight path from the centre to sample k passes through, where the depth complexity jumps
  // without crossing an edge (src/techniques/dcs/shaders/dcs_init.frag).
  struct Placement {
    std::vector<geo::VolumeRule> rules;  // per mesh
    struct Crossing {
      std::uint32_t mesh;
      geo::PathCrossing at;
    };
    std::vector<std::uint32_t> firstCrossing;  // per sample, then the end: a range of `crossings`
    std::vector<Crossing> crossings;
    std::size_t perTriangleMeshes = 0;  // closed meshes given one volume per triangle for this light
    // Triangles in whose plane the centre and every sample lie (a light lying on a face); of
    // them, those whose border a sample's path from the centre meets (a path along the surface
    // across its border is not resolved: dcs refuses); and triangles the light lies against
    // only within rounding (their facing flips from sample to sample: dcs refuses).
    std::size_t coplanarTriangles = 0;
    std::size_t coplanarBorderTriangles = 0;
    std::size_t nearCoplanarTriangles = 0;
    std::string againstMesh;  // the first mesh with any of them, for the message
    // Throws Error(technique) for a light across a coplanar face's border or on a face only
    // within rounding (shadow_volume.cpp); a light lying wholly on a face is exact and passes.
    void refuseLightOnAFace(const std::string& technique, const std::string& light) const;
  };
  // `samples` (null: the centre only, hard-sv) and the ball of `radius` around `centre` that
  // holds them.
  Placement place(const glm::dvec3& centre, const std::vector<glm::vec3>* samples, double radius,
                  const glm::dvec3& eye) const;

  // x lies exactly on an edge or a vertex of an occluding mesh (geo::onTriangleBorder).
  bool onMeshBorder(const glm::dvec3& x) const;

  // Fills counter() with the number of volumes (from pass.light.position) containing each
  // visible point: the count of closed objects plus open surfaces between it and the light,
  // each mesh counted by rules[mesh] (place()). Times the stages "silhouettes" and "shadow
  // volume".
  void count(LightPass& pass, const std::vector<geo::VolumeRule>& rules);

  const gl::Texture& counter() const { return counter_; }
  const std::vector<MeshVolumes>& meshes() const { return meshes_; }
  std::size_t sideEdges() const { return sideEdges_; }
  std::size_t caps() const { return caps_; }
  std::size_t coverTriangles() const { return triangles_; }  // drawn by the last count()
  std::size_t bands() const { return bandCount_; }           // of the last count()
  std::size_t bytes() const;                                 // the counter and the count's buffers

 private:
  std::vector<MeshVolumes> meshes_;
  gl::Program program_;
  // The count's faces and their covers, kept from frame to frame (no reallocation).
  static constexpr std::size_t kCoverBlock = 4096;  // faces a draw (a storage block of 192 KiB)
  struct CoverBlock {
    std::vector<glm::vec2> points;       // window coordinates (volume_cover.h)
    std::vector<std::uint32_t> faces;    // per point, its face in the block
    std::vector<std::uint32_t> indices;  // triangles over the block's points
  };
  // A run of blocks whose faces, points and indices each fit one band (storageBandBytes), in
  // buffers of its own: no buffer of the count passes the GL's storage-block limit or llvmpipe's
  // vertex fetch, however large the scene. Kept from frame to frame.
  struct Band {
    std::size_t firstBlock = 0, endBlock = 0;
    gl::Buffer faces, points, pointFaces, indices;
  };
  std::vector<glm::vec4> faces_;
  std::vector<CoverBlock> blocks_;
  std::vector<Band> bands_;
  std::size_t bandBytes_ = 0, bandCount_ = 0;
  gl::Texture counter_;
  gl::Framebuffer fbo_;
  std::size_t sideEdges_ = 0, caps_ = 0, triangles_ = 0;
};

}  // namespace penumbra
