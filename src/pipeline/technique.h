// The one interface every shadow technique implements, and the explicit table of techniques.
//
// The pipeline (src/pipeline/renderer.h) owns everything techniques share: the G-buffer, the
// light-sample sets, shading and timing. A technique only produces visibility for one light at a
// time: the RGB visibility buffer of DCS eq. 2 and, if it can, per-sample transmittance.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/timer.h"
#include "sampling/light_samples.h"
#include "scene/scene.h"
#include "techniques/raytrace/embree_reference.h"

namespace penumbra {

class GpuScene;  // uploaded geometry + G-buffer, see renderer.h
namespace gl { class Texture; }

// What a technique gets for one light.
struct LightPass {
  const Scene& scene;
  const Light& light;
  int lightIndex;
  const LightSampleSet& samples;  // the set every technique and the reference use
  GpuScene& gpu;                  // geometry buffers, camera, G-buffer textures
  StageTimer& timer;              // techniques time their passes under their own stage names
  // The G-buffer read back to the CPU (read once per frame on first use).
  std::function<const CpuGBuffer&()> cpuGBuffer;
  // Output: an RGBA32F texture (RGB = visibility of eq. 2) the technique renders into or
  // uploads to, and, when the technique provides per-sample results, an R32F 2D array with one
  // layer per sample (transmittance, [0,1]).
  const gl::Texture& visibility;
  const gl::Texture* perSample;  // null unless Technique::providesPerSample()
  // CPU techniques may also hand back their per-sample results directly (avoids a readback).
  std::vector<float>* cpuPerSample;
};

class Technique {
 public:
  Technique() : serial_(nextSerial()) {}
  Technique(const Technique&) = delete;
  Technique& operator=(const Technique&) = delete;
  virtual ~Technique() = default;
  // Unique per object for the life of the process (the renderer prepares a technique it has not
  // seen: an address can be reused by the next technique, a serial cannot).
  std::uint64_t serial() const { return serial_; }
  // Per scene: build what the technique keeps across lights and frames (edge topology, BVH).
  // Create GL objects here or later, never in a constructor: a technique may be constructed
  // before the renderer's context is current.
  virtual void prepare(const Scene& scene, GpuScene& gpu) {}
  // Per light: fill pass.visibility (and pass.perSample if providesPerSample()).
  virtual void renderVisibility(LightPass& pass) = 0;
  // True when the technique gives per-light-sample visibility (enables eq. 6 shading).
  virtual bool providesPerSample() const { return false; }
  // Render-target memory the technique allocated, in bytes (for reports).
  virtual std::size_t memoryBytes() const { return 0; }
  // Numbers about the last frame worth reporting (edges drawn, counter base, passes, ...).
  virtual std::vector<std::pair<std::string, double>> statistics() const { return {}; }

 private:
  static std::uint64_t nextSerial() {
    static std::atomic<std::uint64_t> next{1};
    return next++;
  }
  std::uint64_t serial_;
};

struct TechniqueInfo {
  std::string name;
  std::string description;  // one line for `penumbra list`
  std::function<std::unique_ptr<Technique>()> create;
};

// The explicit name -> factory table (src/techniques/registry.cpp). No static registration.
const std::vector<TechniqueInfo>& techniqueTable();
// Throws penumbra::Error("--technique", ...) listing the known names.
const TechniqueInfo& findTechnique(const std::string& name);

}  // namespace penumbra
