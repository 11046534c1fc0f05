#include "techniques/denoised/denoised.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <optional>
#include <thread>
#include <vector>

#include "core/log.h"
#include "gl/objects.h"
#include "pipeline/renderer.h"
#include "reference/embree_reference.h"
#include "techniques/denoised/ffx_denoiser.h"
#include "techniques/denoised/filtering.h"

namespace penumbra {
namespace {

struct Options {
  std::string denoiser = "ours";  // "ours" (denoise below) or "ffx" (ffx_denoiser.h)
  double clamp = 1.0;             // ffx: the neighbourhood clamp, standard deviations
  int spp = 1;
  bool temporal = true;
  int history = 0;  // 0: N / spp
  int maxRadius = 16;
};

// One light's history: the accumulated ratio, its length, and the surfaces it was computed on.
struct History {
  Image ratio;
  std::vector<int> length;
  std::vector<glm::vec3> position, normal;
  std::vector<std::uint8_t> valid;
  Camera camera;
  glm::dvec3 origin{0.0};
  std::uint32_t frame = 0;
};

// The cross-bilateral filter of `in` (RGB) with per-pixel radius (pixels; < 0.5: unfiltered):
// Gaussian of sigma radius / 2 over the window, times max(n_i . n_j, 0)^16 and
// exp(-|n_i . (p_j - p_i)| / (0.01 d_i)) (d_i the pixel's distance to the eye): surfaces that are
// not the pixel's own plane do not blur into it.
Image crossBilateral(const Image& in, const CpuGBuffer& g, const std::vector<float>& radius) {
  Image out = in;
  const glm::vec3 eye = g.camera.value_or(glm::vec3(0.0f));
  denoise::forEachRow(g.height, [&](int y) {
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = std::size_t(y) * g.width + x;
      const float r = radius[i];
      if (!g.valid[i] || r < 0.5f) continue;
      const int w = int(std::ceil(r));
      const float sigma2 = 2.0f * std::max(0.5f * r, 0.5f) * std::max(0.5f * r, 0.5f);
      const glm::vec3 p = g.position[i], n = g.normal[i];
      const float tolerance = 0.01f * glm::length(p - eye);
      glm::dvec3 sum(0.0);
      double weights = 0.0;
      for (int dy = -w; dy <= w; ++dy)
        for (int dx = -w; dx <= w; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= g.width || yy >= g.height) continue;
          const std::size_t j = std::size_t(yy) * g.width + xx;
          if (!g.valid[j]) continue;
          const float nn = std::max(glm::dot(n, g.normal[j]), 0.0f);
          const float plane = std::abs(glm::dot(n, g.position[j] - p)) / tolerance;
          const float n2 = nn * nn, n4 = n2 * n2, n8 = n4 * n4;
          const double wgt = std::exp(-double(dx * dx + dy * dy) / sigma2 - plane) * double(n8 * n8);
          if (!(wgt > 1e-6)) continue;
          sum += wgt * glm::dvec3(in.at(xx, yy, 0), in.at(xx, yy, 1), in.at(xx, yy, 2));
          weights += wgt;
        }
      if (weights > 0.0)
        for (int c = 0; c < 3; ++c) out.at(x, y, c) = float(sum[c] / weights);
    }
  });
  return out;
}

class RaytraceDenoised final : public Technique {
 public:
  explicit RaytraceDenoised(const Options& o) : o_(o) {}

  // The BVH of the scene as posed (compare --frames prepares each frame's pose); the history is
  // kept: reprojection and the disocclusion test decide what of it still applies.
  void prepare(const Scene& scene, GpuScene&) override { reference_ = std::make_unique<EmbreeReference>(scene); }

  void renderVisibility(LightPass& pass) override {
    const CpuGBuffer& g = pass.cpuGBuffer();
    const LightSampleSet& set = pass.samples;
    const int n = set.count, spp = std::min(o_.spp, n);
    if (spp < o_.spp && !warned_) {
      PLOG_WARN("raytrace-denoised: spp {} exceeds light '{}''s {} samples: {} rays a pixel", o_.spp, pass.light.name,
                n, spp);
      warned_ = true;
    }
    History& h = histories_[pass.lightIndex];
    SparseResult r =
        pass.timer.time("trace", [&] { return reference_->sparseSamples(g, set, spp, h.frame * std::uint32_t(spp)); });
    Image visibility = pass.timer.time("denoise", [&] {
      if (o_.denoiser != "ffx") return denoise(pass, g, r, h, n, spp);
      const denoise::FfxOptions ffx{o_.temporal, o_.history > 0 ? o_.history : std::max(1, n / spp), o_.clamp};
      const Image ratio = denoise::ffxDenoise(g, pass.scene.camera, r.ratio, ffxHistories_[pass.lightIndex], ffx, ffx_);
      meanHistory_ = ffx_.meanHistory;
      return denoise::visibilityFromRatio(g, pass.samples, ratio);
    });
    ++h.frame;
    pass.timer.harness("upload", [&] { pass.visibility.upload(visibility.data.data(), 3); });
    if (pass.cpuVisibility) *pass.cpuVisibility = std::move(visibility);
  }

  std::vector<std::pair<std::string, double>> statistics() const override {
    return {{"spp", double(o_.spp)},
            {"ffx denoiser", o_.denoiser == "ffx" ? 1.0 : 0.0},
            {"uniform tiles", ffx_.uniformTiles},
            {"temporal", o_.temporal ? 1.0 : 0.0},
            {"mean radius", meanRadius_},
            {"mean history", meanHistory_},
            {"rays", reference_ ? reference_->raysCast() : 0.0}};
  }

 private:
  Image denoise(const LightPass& pass, const CpuGBuffer& g, const SparseResult& r, History& h, int n, int spp) {
    const std::size_t pixels = std::size_t(g.width) * g.height;
    const glm::vec3 eye = g.camera.value_or(glm::vec3(0.0f));
    // The penumbra's radius in pixels from the occluders' mean distance over a window (pixels
    // whose rays all reached the light have none: a lit pixel next to a shadow takes its
    // neighbours'), by parallel planes.
    const float halfSize = pass.light.penumbraHalfSize();
    const float footprint = 2.0f * std::tan(glm::radians(pass.scene.camera.fovY) * 0.5f) / float(g.height);
    std::vector<float> radius(pixels, 0.0f);
    const int window = o_.maxRadius;
    denoise::forEachRow(g.height, [&](int y) {
      for (int x = 0; x < g.width; ++x) {
        const std::size_t i = std::size_t(y) * g.width + x;
        if (!g.valid[i]) continue;
        double sum = 0.0;
        int count = 0;
        for (int dy = -window; dy <= window; dy += 2)
          for (int dx = -window; dx <= window; dx += 2) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= g.width || yy >= g.height) continue;
            const float b = r.blocker[std::size_t(yy) * g.width + xx];
            if (b > 0.0f) sum += b, ++count;
          }
        if (count == 0) continue;  // nothing blocks nearby: the ratio is exactly 1 here
        const float blocker = float(sum / count);
        const float toLight = glm::length(pass.light.position - g.position[i]);
        const float width = halfSize * blocker / std::max(toLight - blocker, 1e-3f * toLight);
        const float r = width / (footprint * glm::length(g.position[i] - eye));
        radius[i] = std::isfinite(r) ? std::clamp(r, 0.0f, float(o_.maxRadius)) : float(o_.maxRadius);
      }
    });

    const Image current = crossBilateral(r.ratio, g, radius);
    Image accumulated = r.ratio;
    const int maxHistory = o_.history > 0 ? o_.history : std::max(1, n / spp);
    std::vector<int> length(pixels, 1);
    if (o_.temporal && !h.valid.empty() && h.ratio.width == g.width && h.ratio.height == g.height) {
      const denoise::PreviousView previous =
          denoise::previousView(h.camera, h.origin, float(g.width) / float(g.height));
      for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
          const std::size_t i = std::size_t(y) * g.width + x;
          if (!g.valid[i]) continue;
          glm::vec3 p;
          const long found = denoise::previousPixel(g, i, previous, p);
          if (found < 0) continue;
          const std::size_t j = std::size_t(found);
          const int px = int(found % g.width), py = int(found / g.width);
          const float tolerance = 0.01f * glm::length(g.position[i] - eye);
          if (!h.valid[j] || glm::length(h.position[j] - p) > tolerance || glm::dot(h.normal[j], g.normal[i]) < 0.9f)
            continue;  // disoccluded: another surface was there
          length[i] = std::min(h.length[j] + 1, maxHistory);
          for (int ch = 0; ch < 3; ++ch) {
            const float f = current.at(x, y, ch);
            const float old = std::clamp(h.ratio.at(px, py, ch), f - 0.25f, f + 0.25f);
            accumulated.at(x, y, ch) = old + (r.ratio.at(x, y, ch) - old) / float(length[i]);
          }
        }
    }
    std::vector<float> shrunk(pixels);
    double radiusSum = 0.0, historySum = 0.0;
    std::size_t surfaces = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
      shrunk[i] = radius[i] > 0.0f ? std::max(radius[i] / std::sqrt(float(length[i])), 1.0f) : 0.0f;
      if (g.valid[i]) radiusSum += shrunk[i], historySum += length[i], ++surfaces;
    }
    meanRadius_ = surfaces ? radiusSum / double(surfaces) : 0.0;
    meanHistory_ = surfaces ? historySum / double(surfaces) : 0.0;
    const Image ratio = crossBilateral(accumulated, g, shrunk);
    if (o_.temporal) {
      h.ratio = accumulated;
      h.length = length;
      h.position = g.position;
      h.normal = g.normal;
      h.valid = g.valid;
      h.camera = pass.scene.camera;
      h.origin = g.origin;
    }
    return denoise::visibilityFromRatio(g, pass.samples, ratio);
  }

  Options o_;
  std::unique_ptr<EmbreeReference> reference_;
  std::map<int, History> histories_;
  std::map<int, denoise::FfxHistory> ffxHistories_;
  denoise::FfxStatistics ffx_;
  double meanRadius_ = 0.0, meanHistory_ = 0.0;
  bool warned_ = false;
};

}  // namespace

std::vector<ParamSpec> denoisedParams(const std::string& denoiser) {
  const Options o;
  return {
      ParamSpec::choice("denoiser", denoiser, {"ours", "ffx"},
                        "ours: penumbra-sized cross-bilateral filter; ffx: after FidelityFX's shadow denoiser "
                        "(tile classification, neighbourhood-clamped history, a-trous passes)"),
      ParamSpec::number("clamp", o.clamp, 0.0, 10.0,
                        "ffx: the history clamped to the 7x7 neighbourhood's mean +- this many standard deviations"),
      ParamSpec::integer("spp", o.spp, 1, 64, "shadow rays per pixel and frame (of the pixel's N samples)"),
      ParamSpec::boolean("temporal", o.temporal, "accumulate over frames with reprojection"),
      ParamSpec::integer("history", o.history, 0, 1024,
                         "frames of history at most (0: N / spp, one cycle of the samples)")
          .shown("N / spp"),
      ParamSpec::integer("max-radius", o.maxRadius, 1, 64, "the spatial filter's largest radius, pixels")};
}

std::unique_ptr<Technique> makeRaytraceDenoised(const TechniqueArgs& args) {
  Options o;
  o.denoiser = args.text("denoiser");
  o.clamp = args.number("clamp");
  o.spp = args.integer("spp");
  o.temporal = args.boolean("temporal");
  o.history = args.integer("history");
  o.maxRadius = args.integer("max-radius");
  return std::make_unique<RaytraceDenoised>(o);
}

}  // namespace penumbra
