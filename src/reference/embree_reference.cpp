// CPU ray-traced reference (Embree 3): the transmittance of every (pixel, light sample) segment,
// i.e. 1 - Sat(D(s_i <-> p)) of the DCS paper eq. 1-2 with D computed exactly by ray casting.
// Semi-opaque occluders multiply their (1 - opacity) along the segment (the physically correct
// attenuation the paper's section 3 "Surface opaqueness" says its summed Dr only approximates).
#include "reference/embree_reference.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <string>
#include <thread>

#include "core/error.h"
#include "core/parallel.h"
#include "shading/shading_shared.hpp"

namespace penumbra {
namespace {

// Segment end: the ray stops just before the light sample (t < 1 - 1e-5 of the unnormalised
// direction), so a sample lying on a surface does not shadow itself.
constexpr float kTFar = 1.0f - 1e-5f;

// A hit counted by the occlusion filter for the current ray.
struct CountedHit {
  unsigned geomID, primID;
  float t;
};

// Per-thread scratch: the rays of one stream and, per ray (indexed by RTCRay::id), the hits the
// filter counted and their running transmittance.
struct Scratch {
  std::vector<RTCRay> rays;
  std::vector<std::vector<CountedHit>> hits;
  std::vector<float> transmittance;
  void reset(std::size_t n) {
    rays.clear();
    if (hits.size() < n) hits.resize(n), transmittance.resize(n);
    for (std::size_t i = 0; i < n; ++i) hits[i].clear(), transmittance[i] = 1.0f;
  }
};

// Reached from the filter. RTCIntersectContext must be the first member: Embree passes the
// filter a pointer to it (the extended-context idiom of the Embree tutorials).
struct RayContext {
  RTCIntersectContext rtc;
  const float* opacity;  // per geomID
  Scratch* scratch;
};

// Occlusion filter of semi-opaque geometries: counts the hit and rejects it so that traversal
// continues. Embree may report one crossing several times: a triangle referenced from several
// BVH leaves (spatial splits of RTC_BUILD_QUALITY_HIGH) is reported once per leaf, and a ray
// through an edge or vertex shared by triangles of the same mesh hits each of them (robust mode
// tests edges inclusively; both measured in tests/raytrace_embree.cpp). Both are one surface
// crossing, so a hit is ignored when the same (geomID, primID), or the same geometry at the same
// distance, was already counted for this ray. The ray is found by its id, not by its lane: a
// stream may reach the filter in packets of any size.
void occlusionFilter(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<RayContext*>(const_cast<RTCIntersectContext*>(args->context));
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned id = RTCRayN_id(args->ray, args->N, i);
    const unsigned geomID = RTCHitN_geomID(args->hit, args->N, i);
    const unsigned primID = RTCHitN_primID(args->hit, args->N, i);
    // The hit distance during the filter, in units of the ray's direction: up to 1 (or 2^k for
    // a direction makeRay shortened), hence the tolerance below relative to t.
    const float t = RTCRayN_tfar(args->ray, args->N, i);
    std::vector<CountedHit>& hits = ctx->scratch->hits[id];
    float& tr = ctx->scratch->transmittance[id];
    bool seen = false;
    for (const CountedHit& h : hits) {
      if (h.geomID == geomID && (h.primID == primID || std::abs(h.t - t) <= 1e-6f * std::max(1.0f, t))) {
        seen = true;
        break;
      }
    }
    if (!seen) {
      hits.push_back({geomID, primID, t});
      tr *= 1.0f - ctx->opacity[geomID];
    }
    // Accept (stop, transmittance 0) only when nothing gets through any more.
    if (tr > 0.0f) args->valid[i] = 0;
  }
}

// An alpha-tested geometry (Scene::alphaTested): what its hit filter needs, copied from the scene.
struct AlphaGeometry {
  std::vector<glm::vec2> uvs;  // per vertex
  std::vector<glm::uvec3> triangles;
  std::vector<float> alpha;  // the texture's alpha channel, top row first (as uploaded to GL)
  int width = 0, height = 0;
  float factor = 1.0f, cutoff = 0.5f;

  float texel(float x, float y) const { return alpha[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
  // shading/shaders/alpha_test.h, as the G-buffer and the depth passes decide it.
  bool present(glm::vec2 uv) const {
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return true;
    const glm::vec2 size{float(width), float(height)};
    glm::vec2 first, weight;
    shared::penumbraAlphaTexels(uv, size, first, weight);
    const glm::vec2 a = shared::penumbraWrapTexel(first, size), b = shared::penumbraWrapTexel(first + 1.0f, size);
    return shared::penumbraAlphaPasses(texel(a.x, a.y), texel(b.x, a.y), texel(a.x, b.y), texel(b.x, b.y), weight,
                                       factor, cutoff);
  }
};

// Occlusion filter of alpha-tested geometries: a hit where the texture cuts the surface away is
// rejected (traversal goes on). The hit's texture coordinate from Embree's barycentrics: the point
// is (1 - u - v) v0 + u v1 + v v2 (Embree 3 API, RTCHit).
void alphaFilter(const RTCFilterFunctionNArguments* args) {
  const auto* g = static_cast<const AlphaGeometry*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const glm::uvec3 t = g->triangles[RTCHitN_primID(args->hit, args->N, i)];
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    const glm::vec2 uv = (1.0f - u - v) * g->uvs[t.x] + u * g->uvs[t.y] + v * g->uvs[t.z];
    if (!g->present(uv)) args->valid[i] = 0;
  }
}

// Embree accepts ray origins and directions with |components| <= FLT_LARGE (1.844e18, its
// RayK::valid(); beyond it a debug build aborts: hard case 31, a light of size 1e19). A
// segment towards a sample that far is shortened by an exact power of two 2^k and tfar grows by
// the same 2^k: the ray's points o + t d are the same floats, so the hit (and the shadow) are
// exactly those of the unscaled segment. The scene loader refuses lights beyond float's range.
constexpr float kMaxDirection = 0x1p60f;  // 1.15e18 < FLT_LARGE

RTCRay makeRay(const glm::vec3& o, glm::vec3 d, unsigned id) {
  RTCRay ray;
  float tfar = kTFar;
  const float longest = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  if (longest > kMaxDirection) {
    int e = 0;
    std::frexp(longest / kMaxDirection, &e);  // 2^(e-1) <= longest / 2^60 < 2^e
    d = glm::vec3(std::ldexp(d.x, -e), std::ldexp(d.y, -e), std::ldexp(d.z, -e));
    tfar = std::ldexp(kTFar, e);
  }
  ray.org_x = o.x, ray.org_y = o.y, ray.org_z = o.z;
  ray.dir_x = d.x, ray.dir_y = d.y, ray.dir_z = d.z;
  ray.tnear = 0.0f;
  ray.tfar = tfar;
  ray.time = 0.0f;
  ray.mask = ~0u;
  ray.id = id;
  ray.flags = 0;
  return ray;
}

unsigned threadCount(int requested) {
  if (requested > 0) return unsigned(requested);
  return std::max(1u, std::thread::hardware_concurrency());
}

void checkGBuffer(const CpuGBuffer& g) {
  const std::size_t n = std::size_t(g.width) * g.height;
  PENUMBRA_CHECK(g.width >= 0 && g.height >= 0 && g.position.size() == n && g.normal.size() == n && g.valid.size() == n,
                 "CpuGBuffer arrays do not match width x height");
}

}  // namespace

struct EmbreeReference::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<float> opacity;                                   // per geomID
  std::vector<std::unique_ptr<AlphaGeometry>> alphaGeometries;  // their filters' user data
  unsigned threads = 1;
  mutable std::atomic<std::uint64_t> rays{0};
  std::string lastError;  // set by the device error callback

  // Here rather than in ~EmbreeReference so that a constructor that throws releases them too.
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void throwIfError(const char* what) {
    const RTCError code = rtcGetDeviceError(device);
    if (code != RTC_ERROR_NONE)
      throw Error("embree",
                  std::string(what) + ": " + (lastError.empty() ? "error " + std::to_string(int(code)) : lastError));
  }

  // Transmittances of the rays in s.rays (ray j has id j) into out[j].
  void traceStream(Scratch& s, float* out) const {
    if (s.rays.empty()) return;
    RayContext ctx;
    rtcInitIntersectContext(&ctx.rtc);
    ctx.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // one origin, nearby directions
    ctx.opacity = opacity.data();
    ctx.scratch = &s;
    rtcOccluded1M(scene, &ctx.rtc, s.rays.data(), unsigned(s.rays.size()), sizeof(RTCRay));
    for (std::size_t j = 0; j < s.rays.size(); ++j) {
      std::vector<CountedHit>& hits = s.hits[j];
      if (s.rays[j].tfar < 0.0f) {  // an accepted hit: opaque surface
        out[j] = 0.0f;
        continue;
      }
      // Multiply in a fixed order (by geometry, then primitive), not in traversal order, so the
      // float result does not depend on the BVH or the traversal.
      std::sort(hits.begin(), hits.end(), [](const CountedHit& a, const CountedHit& b) {
        return a.geomID != b.geomID ? a.geomID < b.geomID : a.primID < b.primID;
      });
      float tr = 1.0f;
      for (const CountedHit& h : hits) tr *= 1.0f - opacity[h.geomID];
      out[j] = tr;
    }
  }

  // Visibility of one pixel against `count` samples (positions/luminance arrays of that set),
  // with the conventions of the header: horizon rule, ray origin off the surface. All rays
  // of the pixel go to Embree as one stream.
  glm::vec3 tracePixel(const glm::vec3& p, const glm::vec3& n, const glm::vec3& eye, const glm::vec3* pos,
                       const glm::vec3* lum, int count, float* perSample, Scratch& s, std::vector<int>& sampleOf,
                       std::vector<float>& tr, std::uint64_t& rayCount) const {
    const glm::vec3 o = shared::penumbraShadowOrigin(p, n, eye);
    s.reset(std::size_t(count));
    sampleOf.clear();
    for (int k = 0; k < count; ++k) {
      if (!(glm::dot(n, pos[k] - p) > 0.0f)) continue;  // below the horizon: 0, no ray
      s.rays.push_back(makeRay(o, pos[k] - o, unsigned(s.rays.size())));
      sampleOf.push_back(k);
    }
    tr.assign(s.rays.size(), 0.0f);
    traceStream(s, tr.data());
    rayCount += s.rays.size();
    if (perSample) std::fill(perSample, perSample + count, 0.0f);
    glm::dvec3 sum(0.0);
    for (std::size_t j = 0; j < sampleOf.size(); ++j) {
      const int k = sampleOf[j];
      if (perSample) perSample[k] = tr[j];
      sum += glm::dvec3(lum[k]) * double(tr[j]);  // eq. 2: L_i * (1 - Sat(D)), in sample order
    }
    return glm::vec3(sum / double(count));
  }
};

EmbreeReference::EmbreeReference(const Scene& scene, int threads) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.threads = threadCount(threads);
  const std::string config = "threads=" + std::to_string(m.threads);
  m.device = rtcNewDevice(config.c_str());
  if (!m.device)
    throw Error("embree", "cannot create device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(
      m.device, [](void* user, RTCError, const char* msg) { static_cast<Impl*>(user)->lastError = msg ? msg : ""; },
      &m);

  m.scene = rtcNewScene(m.device);
  m.throwIfError("creating the scene");
  rtcSetSceneFlags(m.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(m.scene, RTC_BUILD_QUALITY_HIGH);

  for (const SceneMesh& sm : scene.meshes) {
    if (sm.material < 0 || sm.material >= int(scene.materials.size()))
      throw Error(sm.name, "material index " + std::to_string(sm.material) + " out of range");
    const float op = std::min(scene.materials[sm.material].opacity, 1.0f);
    // Fully transparent surfaces (opacity 0, e.g. alpha MASK below the cutoff) never occlude:
    // they are left out of the BVH rather than filtered on every hit.
    if (!(op > 0.0f) || sm.mesh.triangles.empty()) continue;
    const std::size_t nv = sm.mesh.positions.size(), nt = sm.mesh.triangles.size();
    for (const glm::uvec3& t : sm.mesh.triangles)
      PENUMBRA_CHECK(t.x < nv && t.y < nv && t.z < nv, "triangle index out of range in " + sm.name);

    RTCGeometry g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
    auto* ib = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt));
    if (!vb || !ib) {
      rtcReleaseGeometry(g);
      m.throwIfError(sm.name.c_str());
      throw Error("embree", "cannot allocate buffers for " + sm.name);
    }
    for (std::size_t i = 0; i < nv; ++i) {
      vb[3 * i] = sm.mesh.positions[i].x;
      vb[3 * i + 1] = sm.mesh.positions[i].y;
      vb[3 * i + 2] = sm.mesh.positions[i].z;
    }
    for (std::size_t i = 0; i < nt; ++i) {
      ib[3 * i] = sm.mesh.triangles[i].x;
      ib[3 * i + 1] = sm.mesh.triangles[i].y;
      ib[3 * i + 2] = sm.mesh.triangles[i].z;
    }
    // Only semi-opaque and alpha-tested geometry gets a filter; opaque hits end traversal at once.
    if (op < 1.0f) rtcSetGeometryOccludedFilterFunction(g, occlusionFilter);
    if (scene.alphaTested(sm.material)) {
      const Material& mat = scene.materials[std::size_t(sm.material)];
      const Image& image = scene.textures[std::size_t(mat.baseColorTexture)].image;
      auto a = std::make_unique<AlphaGeometry>();
      a->uvs = sm.mesh.uvs.size() == nv ? sm.mesh.uvs : std::vector<glm::vec2>(nv, glm::vec2(0.0f));
      a->triangles = sm.mesh.triangles;
      a->width = image.width, a->height = image.height;
      a->alpha.resize(image.pixelCount());
      for (std::size_t i = 0; i < a->alpha.size(); ++i) a->alpha[i] = image.data[i * 4 + 3];
      a->factor = mat.alphaFactor, a->cutoff = mat.alphaCutoff;
      rtcSetGeometryUserData(g, a.get());
      rtcSetGeometryOccludedFilterFunction(g, alphaFilter);
      m.alphaGeometries.push_back(std::move(a));
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(m.scene, g, unsigned(m.opacity.size()));
    rtcReleaseGeometry(g);
    m.opacity.push_back(op);
    m.throwIfError(sm.name.c_str());
  }
  rtcCommitScene(m.scene);
  m.throwIfError("building the BVH");
}

EmbreeReference::~EmbreeReference() = default;

VisibilityResult EmbreeReference::sameSamples(const CpuGBuffer& gbuf, const LightSampleSet& samples) const {
  checkGBuffer(gbuf);
  const int n = samples.count;
  const std::size_t total = std::size_t(samples.setCount) * n;
  PENUMBRA_CHECK(
      n >= 1 && samples.setCount >= 1 && samples.positions.size() == total && samples.luminance.size() == total,
      "LightSampleSet arrays do not match count x setCount");
  VisibilityResult out;
  out.samples = n;
  out.visibility = Image(gbuf.width, gbuf.height, 3, 0.0f);
  out.perSample.assign(std::size_t(gbuf.width) * gbuf.height * n, 0.0f);
  const Impl& m = *impl_;
  PassProgress progress("ray tracer (same samples)", gbuf.height);
  m.rays += parallelRows(
      gbuf.height, m.threads,
      [&](int y, std::uint64_t& rayCount) {
        Scratch scratch;
        std::vector<int> sampleOf;
        std::vector<float> tr;
        for (int x = 0; x < gbuf.width; ++x) {
          const std::size_t i = std::size_t(y) * gbuf.width + x;
          if (!gbuf.valid[i]) continue;  // no surface: visibility 0
          const std::size_t first = std::size_t(samples.setForPixel(x, y)) * n;
          const glm::vec3 p = gbuf.position[i], nrm = gbuf.normal[i];
          const glm::vec3 v =
              m.tracePixel(p, nrm, gbuf.camera.value_or(p + nrm), &samples.positions[first], &samples.luminance[first],
                           n, &out.perSample[i * n], scratch, sampleOf, tr, rayCount);
          for (int c = 0; c < 3; ++c) out.visibility.at(x, y, c) = v[c];
        }
      },
      &progress);
  return out;
}

VisibilityResult EmbreeReference::converged(const CpuGBuffer& gbuf, const Light& light, const Scene& scene,
                                            const shading::IntegratorOptions& options, float time,
                                            std::uint32_t seed) const {
  checkGBuffer(gbuf);
  // Validates the options and the light up front, so errors are thrown here rather than in a worker.
  const shading::LightIntegrator integrator(scene, light, time, options);
  // The shaded image needs the G-buffer's BRDF inputs (a caller may give geometry only).
  const std::size_t n = gbuf.position.size();
  const bool shaded = gbuf.shadingNormal.size() == n && gbuf.baseColor.size() == n && gbuf.material.size() == n;
  VisibilityResult out;
  out.visibility = Image(gbuf.width, gbuf.height, 3, 0.0f);
  out.visibilityVariance = Image(gbuf.width, gbuf.height, 3, 0.0f);
  if (shaded) out.radiance = out.radianceVariance = Image(gbuf.width, gbuf.height, 3, 0.0f);
  std::vector<int> samples(n, 0);
  std::vector<std::uint8_t> capped(n, 0);
  const Impl& m = *impl_;
  PassProgress progress("converged reference", gbuf.height);
  m.rays += parallelRows(
      gbuf.height, m.threads,
      [&](int y, std::uint64_t& rayCount) {
        Scratch scratch;
        const shading::SegmentTracer trace = [&](const glm::vec3& o, const glm::vec3* targets, int count, float* tr) {
          scratch.reset(std::size_t(count));
          for (int j = 0; j < count; ++j) scratch.rays.push_back(makeRay(o, targets[j] - o, unsigned(j)));
          m.traceStream(scratch, tr);
        };
        for (int x = 0; x < gbuf.width; ++x) {
          const std::size_t i = std::size_t(y) * gbuf.width + x;
          if (!gbuf.valid[i]) continue;  // no surface: visibility 0
          shading::SurfacePoint sp;
          sp.p = gbuf.position[i], sp.ng = gbuf.normal[i];
          sp.eye = gbuf.camera.value_or(sp.p + sp.ng);
          sp.origin = shared::penumbraShadowOrigin(sp.p, sp.ng, sp.eye);
          if (shaded) {
            const glm::vec3& mat = gbuf.material[i];
            sp.shaded = true, sp.ns = gbuf.shadingNormal[i], sp.baseColor = gbuf.baseColor[i];
            sp.metallic = mat.x, sp.roughness = mat.y, sp.model = int(mat.z + 0.5f);
          }
          // Seeded by the pixel index: decorrelated (section 5.1) and independent of the thread that
          // computes it. `seed` picks another family of sets (a second estimate, for the noise).
          const std::uint32_t pixelSeed =
              seed == 0 ? std::uint32_t(i) : shared::penumbraHash(std::uint32_t(i) ^ shared::penumbraHash(seed));
          const shading::PixelEstimate e = integrator.estimate(sp, pixelSeed, trace);
          rayCount += e.rays;
          samples[i] = e.samples, capped[i] = e.capped;
          for (int c = 0; c < 3; ++c) {
            out.visibility.at(x, y, c) = float(e.visibility[c]);
            out.visibilityVariance.at(x, y, c) = float(e.visibilityVariance[c]);
            if (shaded)
              out.radiance.at(x, y, c) = float(e.radiance[c]),
                                    out.radianceVariance.at(x, y, c) = float(e.radianceVariance[c]);
          }
        }
      },
      &progress);
  std::int64_t surface = 0, total = 0;
  out.samples = std::numeric_limits<int>::max();
  for (std::size_t i = 0; i < n; ++i) {
    if (!gbuf.valid[i]) continue;
    ++surface, total += samples[i], out.cappedPixels += capped[i];
    out.maxSamples = std::max(out.maxSamples, samples[i]), out.samples = std::min(out.samples, samples[i]);
  }
  if (surface == 0) out.samples = 0;
  out.meanSamples = surface ? double(total) / double(surface) : 0.0;
  return out;
}

SparseResult EmbreeReference::sparseSamples(const CpuGBuffer& gbuf, const LightSampleSet& samples, int spp,
                                            std::uint32_t rotation) const {
  checkGBuffer(gbuf);
  const int n = samples.count;
  PENUMBRA_CHECK(spp >= 1 && spp <= n, "sparseSamples: spp outside 1..N");
  SparseResult out;
  out.rays = spp;
  out.ratio = Image(gbuf.width, gbuf.height, 3, 1.0f);
  out.blocker.assign(std::size_t(gbuf.width) * gbuf.height, 0.0f);
  const Impl& m = *impl_;
  PassProgress progress("sparse rays (raytrace-denoised)", gbuf.height);
  m.rays += parallelRows(
      gbuf.height, m.threads,
      [&](int y, std::uint64_t& rayCount) {
        Scratch scratch;
        std::vector<float> tr;
        std::vector<int> sampleOf, above;
        for (int x = 0; x < gbuf.width; ++x) {
          const std::size_t i = std::size_t(y) * gbuf.width + x;
          if (!gbuf.valid[i]) continue;
          const glm::vec3 p = gbuf.position[i], nrm = gbuf.normal[i];
          const glm::vec3 o = shared::penumbraShadowOrigin(p, nrm, gbuf.camera.value_or(p + nrm));
          const std::size_t first = std::size_t(samples.setForPixel(x, y)) * n;
          const std::uint32_t h = shared::penumbraHash(std::uint32_t(i) ^ 0x9e3779b9u);
          // The rotation runs over the samples above the horizon only: a sample below it is 0 in
          // the unshadowed term too, and tracing one told nothing (such a pixel kept ratio 1 and lit
          // the inside of a closed box, hard case 35).
          above.clear();
          for (int k = 0; k < n; ++k)
            if (glm::dot(nrm, samples.positions[first + k] - p) > 0.0f) above.push_back(k);
          const int candidates = int(above.size()), traced = std::min(spp, candidates);
          scratch.reset(std::size_t(traced));
          sampleOf.clear();
          for (int j = 0; j < traced; ++j) {
            const int k = above[(h + rotation + std::uint32_t(j)) % std::uint32_t(candidates)];
            const glm::vec3& xk = samples.positions[first + k];
            scratch.rays.push_back(makeRay(o, xk - o, unsigned(scratch.rays.size())));
            sampleOf.push_back(k);
          }
          tr.assign(scratch.rays.size(), 0.0f);
          m.traceStream(scratch, tr.data());
          rayCount += scratch.rays.size();
          glm::dvec3 lit(0.0), all(0.0);
          double distance = 0.0;
          int blocked = 0;
          for (std::size_t j = 0; j < sampleOf.size(); ++j) {
            const glm::dvec3 l(samples.luminance[first + sampleOf[j]]);
            lit += l * double(tr[j]);
            all += l;
            if (tr[j] < 1.0f) {  // the nearest occluder along it
              const glm::vec3 xk = samples.positions[first + sampleOf[j]];
              RTCRayHit rh;
              rh.ray = makeRay(o, xk - o, 0);
              rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
              RTCIntersectContext ctx;
              rtcInitIntersectContext(&ctx);
              rtcIntersect1(m.scene, &ctx, &rh);
              ++rayCount;
              if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
                distance +=
                    double(rh.ray.tfar) * double(glm::length(glm::vec3(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z)));
                ++blocked;
              }
            }
          }
          for (int c = 0; c < 3; ++c) out.ratio.at(x, y, c) = all[c] > 0.0 ? float(lit[c] / all[c]) : 1.0f;
          out.blocker[i] = blocked > 0 ? float(distance / blocked) : 0.0f;
        }
      },
      &progress);
  return out;
}

float EmbreeReference::transmittance(const glm::vec3& from, const glm::vec3& to) const {
  Scratch s;
  s.reset(1);
  s.rays.push_back(makeRay(from, to - from, 0));
  float tr = 0.0f;
  impl_->traceStream(s, &tr);
  ++impl_->rays;
  return tr;
}

double EmbreeReference::raysCast() const { return double(impl_->rays.load()); }

}  // namespace penumbra
