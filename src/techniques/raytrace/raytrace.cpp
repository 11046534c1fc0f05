// Technique adapter for the Embree reference (embree_reference.h): reads the G-buffer back, traces
// on the CPU, uploads the visibility buffer (and per-sample transmittance) for shading; the
// converged reference also hands back its own shaded image of each light.
#include "techniques/raytrace/raytrace.h"

#include "gl/objects.h"
#include "pipeline/renderer.h"
#include "techniques/raytrace/embree_reference.h"

namespace penumbra {
namespace {

class Raytrace final : public Technique {
 public:
  explicit Raytrace(int convergedSamples) : converged_(convergedSamples) {}

  void prepare(const Scene& scene, GpuScene&) override {
    reference_ = std::make_unique<EmbreeReference>(scene);
  }

  void renderVisibility(LightPass& pass) override {
    const CpuGBuffer& gbuf = pass.cpuGBuffer();
    VisibilityResult r = pass.timer.time("trace", [&] {
      return converged_ > 0 ? reference_->converged(gbuf, pass.light, pass.scene, converged_)
                            : reference_->sameSamples(gbuf, pass.samples);
    });
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
    if (pass.cpuRadiance && r.radiance.pixelCount() > 0) *pass.cpuRadiance = std::move(r.radiance);
  }

  bool providesPerSample() const override { return converged_ == 0; }
  bool shadesLights() const override { return converged_ > 0; }

 private:
  int converged_;
  std::unique_ptr<EmbreeReference> reference_;
};

}  // namespace

std::unique_ptr<Technique> makeRaytraceSameSamples() { return std::make_unique<Raytrace>(0); }
std::unique_ptr<Technique> makeRaytraceConverged(int samples) { return std::make_unique<Raytrace>(samples); }

}  // namespace penumbra
