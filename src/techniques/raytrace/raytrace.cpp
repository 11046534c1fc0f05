// Technique adapter for the Embree reference (embree_reference.h): reads the G-buffer back, traces
// on the CPU, uploads the visibility buffer (and per-sample transmittance) for shading; the
// converged reference also hands back its own shaded image of each light and its noise.
#include "techniques/raytrace/raytrace.h"

#include <algorithm>
#include <optional>
#include <string>

#include "core/error.h"
#include "gl/objects.h"
#include "pipeline/renderer.h"
#include "reference/embree_reference.h"

namespace penumbra {
namespace {

class Raytrace final : public Technique {
 public:
  explicit Raytrace(std::optional<shading::IntegratorOptions> converged) : converged_(converged) {}

  void prepare(const Scene& scene, GpuScene&) override { reference_ = std::make_unique<EmbreeReference>(scene); }

  void renderVisibility(LightPass& pass) override {
    const CpuGBuffer& gbuf = pass.cpuGBuffer();
    VisibilityResult r = pass.timer.time("trace", [&] {
      return converged_ ? reference_->converged(gbuf, pass.light, pass.scene, *converged_)
                        : reference_->sameSamples(gbuf, pass.samples);
    });
    if (converged_) {
      if (pass.lightIndex == 0) stats_ = {};
      stats_.lights += 1;
      stats_.meanSamples += r.meanSamples;
      stats_.maxSamples = std::max(stats_.maxSamples, r.maxSamples);
      stats_.capped += double(r.cappedPixels);
    }
    // Uploading the CPU's result for the pipeline's shading is the harness's work, not the trace's.
    pass.timer.harness("upload", [&] {
      pass.visibility.upload(r.visibility.data.data(), 3);
      if (pass.perSample && !r.perSample.empty()) {
        std::size_t n = r.visibility.pixelCount(), N = std::size_t(r.samples);
        std::vector<float> layer(n);
        for (std::size_t k = 0; k < N; ++k) {
          for (std::size_t i = 0; i < n; ++i) layer[i] = r.perSample[i * N + k];
          pass.perSample->upload(layer.data(), 1, int(k));
        }
      }
    });
    if (pass.cpuPerSample) *pass.cpuPerSample = std::move(r.perSample);
    if (pass.cpuVisibility) *pass.cpuVisibility = std::move(r.visibility);
    if (pass.cpuShading && r.radiance.pixelCount() > 0)
      *pass.cpuShading = {std::move(r.radiance), std::move(r.radianceVariance), std::move(r.visibilityVariance)};
  }

  bool providesPerSample() const override { return !converged_; }
  bool shadesLights() const override { return converged_.has_value(); }

  std::vector<std::pair<std::string, double>> statistics() const override {
    if (!converged_ || stats_.lights == 0) return {};
    return {{"light samples per pixel (mean over lights)", stats_.meanSamples / stats_.lights},
            {"light samples per pixel (most)", double(stats_.maxSamples)},
            {"pixels stopped at the cap (sum over lights)", stats_.capped}};
  }

 private:
  std::optional<shading::IntegratorOptions> converged_;
  std::unique_ptr<EmbreeReference> reference_;
  struct {
    int lights = 0, maxSamples = 0;
    double meanSamples = 0.0, capped = 0.0;
  } stats_;
};

}  // namespace

std::unique_ptr<Technique> makeRaytraceSameSamples() { return std::make_unique<Raytrace>(std::nullopt); }

std::vector<ParamSpec> raytraceConvergedParams() {
  const shading::IntegratorOptions o;
  return {
      ParamSpec::integer("reference-samples", o.minSamples, 1, 1 << 20,
                         "light samples per pixel at least (the visibility buffer's)"),
      ParamSpec::integer("reference-max-samples", o.maxSamples, 1, 1 << 24,
                         "light samples per pixel at most (and as many BRDF samples)"),
      ParamSpec::number(
          "reference-target", o.target, 0.0, 1.0,
          "the shaded radiance's standard error relative to the pixel's largest channel (0: every pixel to the cap)"),
      ParamSpec::integer("reference-batch", o.batch, 1, 65536,
                         "samples of each strategy per batch (the noise is the spread of the batches)"),
      ParamSpec::boolean("reference-mis", o.brdfSampling,
                         "sample the BRDF too, combined with the light samples by MIS (0: light samples only)")};
}

std::unique_ptr<Technique> makeRaytraceConverged(const TechniqueArgs& args) {
  shading::IntegratorOptions o;
  o.minSamples = args.integer("reference-samples");
  o.maxSamples = args.integer("reference-max-samples");
  o.target = args.number("reference-target");
  o.batch = args.integer("reference-batch");
  o.brdfSampling = args.boolean("reference-mis");
  if (o.maxSamples < o.minSamples)
    throw Error(
        "reference-max-samples",
        "is below reference-samples (" + std::to_string(o.maxSamples) + " < " + std::to_string(o.minSamples) + ")",
        ExitCode::Usage);
  return std::make_unique<Raytrace>(o);
}

}  // namespace penumbra
