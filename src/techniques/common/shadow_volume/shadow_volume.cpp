#include "techniques/common/shadow_volume/shadow_volume.h"

#include <algorithm>
#include <cstddef>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "core/parallel.h"
#include "pipeline/renderer.h"
#include "techniques/common/shadow_volume/volume_count.hpp"
#include "techniques/common/shadow_volume/volume_cover.h"

namespace penumbra {
namespace {

// Where an area light (centre and samples) lies against triangle t's plane: In, the centre and
// every sample exactly in it (facing 0: the plane does not occlude them, silhouette.h's
// convention); WithinRounding, not exactly, but every one within 2^-18 of the magnitude of its
// coordinates along the plane's normal (a face the light was meant to lie on, off by the
// rounding of a transform: a light 1e-7 behind it is occluded by it, exactly, where the
// reference's rays, which stop 1e-5 short of the sample, pass; a light of size 7e18 4 above a
// floor is not); else Off, decided at the first point that is neither.
enum class AgainstPlane { Off, In, WithinRounding };

AgainstPlane againstPlane(const geo::EdgeTopology& topology, std::uint32_t t, const glm::dvec3& centre,
                          const std::vector<glm::vec3>& samples) {
  const glm::dvec3 p0(topology.weldedPositions[topology.weldedTriangles[t].x]), normal = topology.faceNormals[t];
  const double len = glm::length(normal);
  if (!(len > 0.0)) return AgainstPlane::Off;
  const glm::dvec3 n = normal / len;
  bool exact = true;
  // False: this point is off the plane by more than rounding.
  auto against = [&](const glm::dvec3& x) {
    if (geo::triangleFacing(topology, t, x) == 0) return true;
    exact = false;
    const double magnitude = glm::dot(glm::abs(n), glm::max(glm::abs(x), glm::abs(p0)));
    return std::abs(glm::dot(n, x - p0)) <= magnitude * 0x1p-18;
  };
  if (!against(centre)) return AgainstPlane::Off;
  for (const glm::vec3& x : samples)
    if (!against(glm::dvec3(x))) return AgainstPlane::Off;
  return exact ? AgainstPlane::In : AgainstPlane::WithinRounding;
}

// Of the triangles the light lies in (`in`), those with an edge on the border of that flat
// region (an open edge, or one whose other triangles are not all in it) that a sample's path
// from the centre meets. Edges inside the region (a ceiling's diagonal) are fine: measured exact.
std::size_t acrossBorder(const geo::EdgeTopology& topology, const std::vector<std::uint32_t>& in,
                         const glm::dvec3& centre, const std::vector<glm::vec3>& samples) {
  std::size_t count = 0;
  const auto isIn = [&](std::uint32_t t) { return std::find(in.begin(), in.end(), t) != in.end(); };
  for (std::uint32_t t : in) {
    const glm::uvec3& tri = topology.weldedTriangles[t];
    const std::uint32_t idx[3] = {tri.x, tri.y, tri.z};
    bool crossed = false;
    for (int i = 0; i < 3 && !crossed; ++i) {
      const std::size_t e = geo::findEdge(topology, idx[i], idx[(i + 1) % 3]);
      if (e == topology.edges.size()) continue;
      const geo::EdgeTopology::Edge& edge = topology.edges[e];
      bool inner = edge.incidenceCount == 2;
      for (std::uint32_t k = 0; k < edge.incidenceCount && inner; ++k)
        inner = isIn(topology.incidences[edge.firstIncidence + k].triangle);
      if (inner) continue;
      const glm::dvec3 u(topology.weldedPositions[idx[i]]), v(topology.weldedPositions[idx[(i + 1) % 3]]);
      for (std::size_t k = 0; k < samples.size() && !crossed; ++k)
        crossed = geo::pathMeetsSegment(topology, t, u, v, centre, glm::dvec3(samples[k]));
    }
    count += crossed;
  }
  return count;
}

}  // namespace

std::size_t storageBandBytes(std::size_t requested) {
  std::size_t band = std::size_t(256) << 20;
  if (gl::limits().maxStorageBlockSize > 0) band = std::min(band, std::size_t(gl::limits().maxStorageBlockSize));
  return requested > 0 ? std::min(band, requested) : band;
}

ParamSpec bandBytesParam() {
  return ParamSpec::integer("band-bytes", 0, 0, 1 << 30,
                            "the most bytes one band of the buffers sized from the scene holds (edges, volume faces "
                            "and their covers, each band bound and drawn on its own); 0: the GL's storage-block limit "
                            "(llvmpipe 128 MiB), at least 64 KiB otherwise; tests set it small to split modest scenes")
      .shown("the GL's limit");
}

std::size_t readBandBytes(const TechniqueArgs& args) {
  const int bytes = args.integer("band-bytes");
  if (bytes > 0 && std::size_t(bytes) < kMinBandBytes)
    throw Error("param", fmt::format("band-bytes: 0 or at least {}, got {}", kMinBandBytes, bytes), ExitCode::Usage);
  return std::size_t(bytes);
}

std::size_t ShadowVolumeCounter::bytes() const {
  std::size_t out = counter_ ? counter_.bytes() : 0;
  for (const Band& b : bands_) out += b.faces.size() + b.points.size() + b.pointFaces.size() + b.indices.size();
  return out;
}

void ShadowVolumeCounter::prepare(const Scene& scene, GpuScene& gpu, const std::vector<int>& units, int opaqueUnits) {
  PENUMBRA_CHECK(units.empty() || units.size() == scene.meshes.size(), "ShadowVolumeCounter: one unit count per mesh");
  meshes_.clear();
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    MeshVolumes v;
    v.topology = geo::buildEdgeTopology(scene.meshes[i].mesh);
    v.name = scene.meshes[i].name;
    // A fully transparent material (opacity 0: glTF MASK below its cutoff, a scene file's opacity
    // 0) never occludes, whatever the caller's units say: the ray tracer leaves it out of its BVH
    // and the shadow maps never draw it.
    const int material = scene.meshes[i].material;
    const bool transparent = material >= 0 && material < int(scene.materials.size()) &&
                             !(scene.materials[std::size_t(material)].opacity > 0.0f);
    v.units = transparent ? 0 : units.empty() ? 1 : units[i];
    v.rule = v.units < opaqueUnits ? geo::VolumeRule::PerTriangle : geo::volumeRuleFor(v.topology);
    meshes_.push_back(std::move(v));
  }
  bands_.clear();
  program_ = gl::Program({"hardsv_volume.vert", "hardsv_volume.frag"});
  counter_ = gl::Texture::make2D(GL_R32F, gpu.width(), gpu.height());
  fbo_ = gl::Framebuffer({&counter_}, &gpu.depth());
}

ShadowVolumeCounter::Placement ShadowVolumeCounter::place(const glm::dvec3& centre,
                                                          const std::vector<glm::vec3>* samples, double radius,
                                                          const glm::dvec3& eye) const {
  Placement out;
  const std::size_t n = samples ? samples->size() : 0;
  std::vector<std::vector<Placement::Crossing>> perSample(n);
  for (std::uint32_t mi = 0; mi < meshes_.size(); ++mi) {
    const MeshVolumes& m = meshes_[mi];
    out.rules.push_back(m.rule);
    if (m.units == 0) continue;
    std::vector<geo::PathCrossing> found;
    std::vector<std::size_t> foundStart(n + 1, 0);
    if (n > 0) {
      std::vector<std::uint32_t> near = geo::trianglesNearBall(m.topology, centre, radius);
      // An area light against a triangle's plane. One sample (a point light, the centre) has no
      // path along a surface, so nothing to check.
      std::vector<std::uint32_t> in;
      std::size_t rounding = 0;
      for (std::uint32_t t : n > 1 ? near : std::vector<std::uint32_t>{}) {
        const AgainstPlane a = againstPlane(m.topology, t, centre, *samples);
        if (a == AgainstPlane::In) in.push_back(t);
        rounding += a == AgainstPlane::WithinRounding;
      }
      const std::size_t border = acrossBorder(m.topology, in, centre, *samples);
      out.coplanarTriangles += in.size();
      out.coplanarBorderTriangles += border;
      out.nearCoplanarTriangles += rounding;
      if ((border > 0 || rounding > 0) && out.againstMesh.empty()) out.againstMesh = m.name;
      for (std::size_t k = 0; k < n; ++k) {
        foundStart[k] = found.size();
        if (!near.empty()) geo::pathCrossings(m.topology, near, centre, glm::dvec3((*samples)[k]), found);
      }
      foundStart[n] = found.size();
      for (std::size_t k = 0; k < n; ++k)
        for (std::size_t j = foundStart[k]; j < foundStart[k + 1]; ++j) perSample[k].push_back({mi, found[j]});
    }
    if (m.rule != geo::VolumeRule::ClosedFrontFaces) continue;
    const geo::PointLocation atEye = geo::locatePoint(m.topology, eye), atCentre = geo::locatePoint(m.topology, centre);
    bool closedRule = !atEye.onSurface && !atCentre.onSurface && atCentre.winding <= atEye.winding;
    // A sample on the surface (its path ends on a triangle) has no cell.
    for (std::size_t k = 0; k < n && closedRule; ++k) {
      const std::optional<int> w = geo::windingAtPathEnd(
          atCentre.winding, std::span(found.data() + foundStart[k], foundStart[k + 1] - foundStart[k]));
      closedRule = w && *w <= atEye.winding;
    }
    if (!closedRule) {
      out.rules[mi] = geo::VolumeRule::PerTriangle;
      ++out.perTriangleMeshes;
    }
  }
  out.firstCrossing.reserve(n + 1);
  for (std::size_t k = 0; k < n; ++k) {
    out.firstCrossing.push_back(std::uint32_t(out.crossings.size()));
    out.crossings.insert(out.crossings.end(), perSample[k].begin(), perSample[k].end());
  }
  out.firstCrossing.push_back(std::uint32_t(out.crossings.size()));
  return out;
}

// A light lying on a face is exact while no sample's path from the centre meets the face's
// border (a light flush with a ceiling); across the border the edge events and the path
// crossings coincide and dcs's counts were silently wrong (a box touching a ceiling light from
// below: 220 pixels off by 2 of 32 samples). Refused, as is a face the light lies on only within
// rounding (a light 1e-7 behind a ceiling is occluded by it, exactly, where the reference's rays
// pass: visibility RMSE 0.93, silently).
void ShadowVolumeCounter::Placement::refuseLightOnAFace(const std::string& technique, const std::string& light) const {
  if (coplanarBorderTriangles > 0)
    throw Error(technique, fmt::format("light '{}' lies in the plane of {} triangle(s) of '{}' and its samples reach "
                                       "across their border: counts along a surface across its edge are not resolved "
                                       "(move the light off the face, or use raytrace)",
                                       light, coplanarBorderTriangles, againstMesh));
  if (nearCoplanarTriangles > 0)
    throw Error(technique, fmt::format("light '{}' lies on {} triangle(s) of '{}' only within rounding (its samples "
                                       "all within 2^-18 of their coordinates of their planes, not in them): put it "
                                       "exactly on the face or clearly off it",
                                       light, nearCoplanarTriangles, againstMesh));
}

bool ShadowVolumeCounter::onMeshBorder(const glm::dvec3& x) const {
  for (const MeshVolumes& m : meshes_)
    if (m.units != 0 && geo::onTriangleBorder(m.topology, x)) return true;
  return false;
}

namespace {
// A face's corners for its cover (world points, w = 0 at infinity), from its storage-block
// record (src/techniques/common/shadow_volume/shaders/hardsv_volume.frag): a side's quad b -> a -> a_inf -> b_inf with
// (a, b) = (v0, v1) turned for a negative weight (common/shadow_volume/shaders/volume_count.h penumbraSideCount), a
// near cap's triangle, a far cap's triangle at infinity reversed.
int faceCorners(const glm::vec4* f, glm::dvec4 corners[4]) {
  const glm::dvec3 a(f[0]), b(f[1]), c(f[2]);
  switch (int(f[1].w)) {
    case PENUMBRA_VOLUME_SIDE: {
      const bool turned = f[0].w < 0.0f;
      const glm::dvec3 u = turned ? b : a, v = turned ? a : b;
      corners[0] = glm::dvec4(v, 1.0), corners[1] = glm::dvec4(u, 1.0);
      corners[2] = glm::dvec4(u, 0.0), corners[3] = glm::dvec4(v, 0.0);
      return 4;
    }
    case PENUMBRA_VOLUME_NEAR_CAP:
      corners[0] = glm::dvec4(a, 1.0), corners[1] = glm::dvec4(b, 1.0), corners[2] = glm::dvec4(c, 1.0);
      return 3;
    default:
      corners[0] = glm::dvec4(a, 0.0), corners[1] = glm::dvec4(c, 0.0), corners[2] = glm::dvec4(b, 0.0);
      return 3;
  }
}

// Grows `buffer` (recreated, contents lost) to hold at least `bytes`, with room up to `cap`.
void reserve(gl::Buffer& buffer, std::size_t bytes, std::size_t cap) {
  if (buffer.size() < bytes || buffer.id() == 0)
    buffer = gl::Buffer(std::max<std::size_t>({std::min(bytes + bytes / 2, cap), bytes, 1024}), nullptr);
}
}  // namespace

void ShadowVolumeCounter::count(LightPass& pass, const std::vector<geo::VolumeRule>& rules) {
  PENUMBRA_CHECK(rules.size() == meshes_.size(), "ShadowVolumeCounter: one volume rule per mesh");
  const glm::dvec3 light(pass.light.position);
  // The faces, three vec4 each (src/techniques/common/shadow_volume/shaders/hardsv_volume.frag: (a, weight), (b, kind),
  // (c, 0)).
  faces_.clear();
  sideEdges_ = caps_ = 0;
  pass.timer.time("silhouettes", [&] {
    for (std::size_t mi = 0; mi < meshes_.size(); ++mi) {
      const MeshVolumes& m = meshes_[mi];
      if (m.units == 0) continue;
      auto sil = geo::extractPointSilhouette(m.topology, light, rules[mi]);
      const auto& P = m.topology.weldedPositions;
      for (auto& s : sil.sides) {
        const auto& e = m.topology.edges[s.edge];
        // The edge in its own order, m_e signed: the plane decision of the count must see the
        // same (v0, v1) as dcs's edge buffer.
        faces_.insert(faces_.end(), {glm::vec4(P[e.v0], float(s.multiplicity * m.units)),
                                     glm::vec4(P[e.v1], float(PENUMBRA_VOLUME_SIDE)), glm::vec4(0.0f)});
        ++sideEdges_;
      }
      for (std::size_t t = 0; t < sil.capSign.size(); ++t) {
        if (sil.capSign[t] == 0) continue;
        const auto& tri = m.topology.weldedTriangles[t];
        // c_t = -1 (back-facing triangle of an open mesh): reverse it so the cap faces the light.
        const glm::uvec3 o = sil.capSign[t] > 0 ? tri : glm::uvec3(tri.x, tri.z, tri.y);
        for (int kind : {PENUMBRA_VOLUME_NEAR_CAP, PENUMBRA_VOLUME_FAR_CAP})
          faces_.insert(faces_.end(),
                        {glm::vec4(P[o.x], float(m.units)), glm::vec4(P[o.y], float(kind)), glm::vec4(P[o.z], 0.0f)});
        ++caps_;
      }
    }
  });

  // Each face's cover (volume_cover.h) as a fan of triangles, in blocks of faces on every core
  // (deterministic: each block's output lands in its place). A block is one draw, its faces a
  // range of its band's storage block; it holds a quarter of a band's faces at most (a cover
  // has about 4-6 points, so its points and indices fit too), a multiple of 16 faces (768 bytes,
  // a multiple of any GL's storage-buffer offset alignment).
  const std::size_t bandBytes = storageBandBytes(bandBytes_);
  const std::size_t blockFaces =
      std::clamp<std::size_t>(bandBytes / (4 * 3 * sizeof(glm::vec4)) / 16 * 16, 16, kCoverBlock);
  const std::size_t faceCount = faces_.size() / 3;
  const std::size_t blocks = (faceCount + blockFaces - 1) / blockFaces;
  if (blocks_.size() < blocks) blocks_.resize(blocks);
  CoverView view;
  view.clipFromWorld = glm::dmat4(pass.gpu.clipFromWorld());
  view.viewport = glm::dvec2(pass.gpu.width(), pass.gpu.height());
  view.clipNear = 0.5 * double(pass.scene.camera.zNear);
  view.light = light;
  view.margin = coverMargin(gl::limits().subpixelBits);
  view.focalPixels =
      0.5 * view.viewport.x *
      glm::length(glm::dvec3(view.clipFromWorld[0][0], view.clipFromWorld[1][0], view.clipFromWorld[2][0]));
  pass.timer.time("volume covers", [&] {
    parallelRows(int(blocks), 0, [&](int block, std::uint64_t&) {
      CoverBlock& b = blocks_[std::size_t(block)];
      b.points.clear();
      b.faces.clear();
      b.indices.clear();
      const std::size_t first = std::size_t(block) * blockFaces, end = std::min(faceCount, first + blockFaces);
      glm::dvec4 corners[4];
      for (std::size_t f = first; f < end; ++f) {
        const std::uint32_t base = std::uint32_t(b.points.size());
        const std::size_t n = appendCover(view, corners, faceCorners(&faces_[3 * f], corners), b.points);
        for (std::uint32_t i = 2; i < n; ++i) b.indices.insert(b.indices.end(), {base, base + i - 1, base + i});
        b.faces.insert(b.faces.end(), n, std::uint32_t(f - first));
      }
    });
  });

  pass.timer.time("shadow volume", [&] {
    // The bands: runs of blocks whose faces, points and indices each fit bandBytes.
    std::vector<std::pair<std::size_t, std::size_t>> runs;  // [first, end) blocks
    std::size_t faceBytes = 0, pointBytes = 0, indexBytes = 0, indices = 0;
    for (std::size_t k = 0; k < blocks; ++k) {
      const CoverBlock& b = blocks_[k];
      const std::size_t f = std::min(faceCount - k * blockFaces, blockFaces) * 3 * sizeof(glm::vec4),
                        p = b.points.size() * sizeof(glm::vec2), i = b.indices.size() * sizeof(std::uint32_t);
      if (f > bandBytes || p > bandBytes || i > bandBytes)
        throw Error("param",
                    fmt::format("band-bytes: the covers of {} faces need {:.3g} MiB, more than a band holds "
                                "({:.3g} MiB): a larger one",
                                blockFaces, double(std::max({f, p, i})) / 1048576.0, double(bandBytes) / 1048576.0));
      if (runs.empty() || faceBytes + f > bandBytes || pointBytes + p > bandBytes || indexBytes + i > bandBytes) {
        runs.emplace_back(k, k);
        faceBytes = pointBytes = indexBytes = 0;
      }
      runs.back().second = k + 1;
      faceBytes += f, pointBytes += p, indexBytes += i;
      indices += b.indices.size();
    }
    if (bands_.size() < runs.size()) bands_.resize(runs.size());
    bandCount_ = runs.size();
    fbo_.bind();
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, zero);
    // No depth test: the fragment shader decides exactly which faces the view ray meets beyond
    // the visible point (hardsv_volume.frag).
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    program_.use();
    program_.set("lightPosition", pass.light.position);
    program_.set("eyePosition", pass.gpu.cameraPosition());
    program_.set("viewport", glm::vec2(pass.gpu.width(), pass.gpu.height()));
    for (std::size_t r = 0; r < runs.size(); ++r) {
      Band& band = bands_[r];
      band.firstBlock = runs[r].first, band.endBlock = runs[r].second;
      const std::size_t firstFace = band.firstBlock * blockFaces,
                        endFace = std::min(faceCount, band.endBlock * blockFaces);
      std::size_t points = 0, bandIndices = 0;
      for (std::size_t k = band.firstBlock; k < band.endBlock; ++k)
        points += blocks_[k].points.size(), bandIndices += blocks_[k].indices.size();
      if (bandIndices == 0) continue;
      reserve(band.faces, (endFace - firstFace) * 3 * sizeof(glm::vec4), bandBytes);
      reserve(band.points, points * sizeof(glm::vec2), bandBytes);
      reserve(band.pointFaces, points * sizeof(std::uint32_t), bandBytes);
      reserve(band.indices, bandIndices * sizeof(std::uint32_t), bandBytes);
      band.faces.write(&faces_[3 * firstFace], (endFace - firstFace) * 3 * sizeof(glm::vec4));
      std::size_t p = 0, i = 0;
      for (std::size_t k = band.firstBlock; k < band.endBlock; ++k) {
        const CoverBlock& b = blocks_[k];
        if (b.points.empty()) continue;
        band.points.write(b.points.data(), b.points.size() * sizeof(glm::vec2), p * sizeof(glm::vec2));
        band.pointFaces.write(b.faces.data(), b.faces.size() * sizeof(std::uint32_t), p * sizeof(std::uint32_t));
        band.indices.write(b.indices.data(), b.indices.size() * sizeof(std::uint32_t), i * sizeof(std::uint32_t));
        p += b.points.size(), i += b.indices.size();
      }
      gl::VertexArray vao = gl::VertexArray::create();
      vao.vertexBuffer(band.points, sizeof(glm::vec2), 0).attribute(0, 2, 0, 0);
      vao.vertexBuffer(band.pointFaces, sizeof(std::uint32_t), 1).attributeInt(1, 1, 0, 1);
      vao.elementBuffer(band.indices);
      vao.bind();
      p = i = 0;
      for (std::size_t k = band.firstBlock; k < band.endBlock; ++k) {
        const CoverBlock& b = blocks_[k];
        if (b.indices.empty()) {
          p += b.points.size();
          continue;
        }
        const std::size_t first = k * blockFaces, n = std::min(faceCount - first, blockFaces);
        band.faces.bindRange(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_VOLUME_FACES,
                             3 * (first - firstFace) * sizeof(glm::vec4), 3 * n * sizeof(glm::vec4));
        glDrawElementsBaseVertex(GL_TRIANGLES, GLsizei(b.indices.size()), GL_UNSIGNED_INT,
                                 reinterpret_cast<const void*>(i * sizeof(std::uint32_t)), GLint(p));
        p += b.points.size(), i += b.indices.size();
      }
    }
    glDisable(GL_BLEND);
    triangles_ = indices / 3;
  });
}

}  // namespace penumbra
