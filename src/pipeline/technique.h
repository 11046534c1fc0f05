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
  // CPU techniques may also hand back their per-sample results and their RGB visibility
  // directly (the harness then reads neither back).
  std::vector<float>* cpuPerSample;
  Image* cpuVisibility;
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
  // Per pixel of the last light (top row first), 1 where the technique left the visibility
  // unshadowed by design rather than computing it (shadow maps: receivers beyond max-angle);
  // empty when there are none. compare counts them and writes their mask (issue 14).
  virtual std::vector<std::uint8_t> unshadowedPixels() const { return {}; }

 private:
  static std::uint64_t nextSerial() {
    static std::atomic<std::uint64_t> next{1};
    return next++;
  }
  std::uint64_t serial_;
};

// Parameters of techniques from the command line (`--param key=value`, repeatable). One set is
// shared by every technique of a run: each technique reads the keys it knows (get* records
// them as known and consumed); `checkConsumed` then refuses a key no technique read, naming the
// keys that were known, so a misspelt parameter is never silently dropped.
class TechniqueParams {
 public:
  TechniqueParams() = default;
  // "key=value" strings; throws Error("--param") for a malformed one or a repeated key.
  explicit TechniqueParams(const std::vector<std::string>& keyValues);
  int getInt(const std::string& key, int fallback, int lo, int hi) const;
  double getDouble(const std::string& key, double fallback, double lo, double hi) const;
  bool getBool(const std::string& key, bool fallback) const;
  bool empty() const { return values_.empty(); }
  // Throws Error("--param") if a given key was read by no technique created with these params.
  void checkConsumed() const;
  // "key=value" of every given key, for reports.
  std::vector<std::string> given() const;
  // "key=value" of the given keys some technique created with these params read.
  std::vector<std::string> read() const;
  // Counts `other`'s reads as reads of these params (one check over techniques created with
  // separate copies, e.g. one per technique and sweep preset).
  void noteReads(const TechniqueParams& other);

 private:
  const std::string* find(const std::string& key) const;
  std::vector<std::pair<std::string, std::string>> values_;
  mutable std::vector<std::string> known_, consumed_;
};

struct TechniqueInfo {
  std::string name;
  std::string description;  // one line for `penumbra list`
  std::function<std::unique_ptr<Technique>(const TechniqueParams&)> create;
};

// The explicit name -> factory table (src/techniques/registry.cpp). No static registration.
const std::vector<TechniqueInfo>& techniqueTable();
// Throws penumbra::Error("--technique", ...) listing the known names.
const TechniqueInfo& findTechnique(const std::string& name);
// findTechnique(name).create(params).
std::unique_ptr<Technique> makeTechnique(const std::string& name, const TechniqueParams& params = {});

}  // namespace penumbra
