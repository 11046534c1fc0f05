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

#include "core/image.h"
#include "core/timer.h"
#include "sampling/light_samples.h"
#include "scene/gbuffer.h"
#include "scene/scene.h"

namespace penumbra {

class GpuScene;  // uploaded geometry + G-buffer, see renderer.h
namespace gl {
class Texture;
}

// What a technique that shades a light itself (the converged reference: its own samples, not the
// pass's set) hands back: the light's outgoing radiance (RGB), which the pipeline adds to the
// image instead of shading the light, and the variance of each pixel's estimate of it and of the
// visibility buffer (its own noise; empty where it has no estimate).
struct CpuShading {
  Image radiance;
  Image radianceVariance;
  Image visibilityVariance;
};

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
  // A technique that shades the light itself (Technique::shadesLights) fills this.
  CpuShading* cpuShading;
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
  // Lights that a closed opaque mesh separates from everything the camera sees are culled for
  // it, their visibility 0 (pipeline/enclosure.h): the techniques that see the occluders only
  // from the light centre.
  virtual bool cullsSeparatedLights() const { return false; }
  // True when the technique shades every light itself (LightPass::cpuShading; the converged
  // reference): the pipeline's shading mode does not apply to it.
  virtual bool shadesLights() const { return false; }
  // Render-target memory the technique allocated, in bytes (for reports).
  virtual std::size_t memoryBytes() const { return 0; }
  // Numbers about the last frame worth reporting (edges drawn, counter base, passes, ...).
  virtual std::vector<std::pair<std::string, double>> statistics() const { return {}; }
  // Per pixel of the last light (top row first), 1 where the technique left the visibility
  // unshadowed by design rather than computing it (shadow maps: receivers beyond max-angle);
  // empty when there are none. compare counts them and writes their mask.
  virtual std::vector<std::uint8_t> unshadowedPixels() const { return {}; }
  // Whether its occluders have the holes of alpha-tested materials (Scene::alphaTested) as the
  // reference's rays do: every pass that draws occluders through GpuScene::drawTriangles tests
  // the alpha (it refuses a program without the test). Shadow volumes built from the meshes'
  // edges cannot see a texture's outline (hard-sv, dcs*: false); the Renderer then notes it in
  // every frame of a scene with such materials, and the error against the reference measures it.
  virtual bool seesAlphaTest() const { return true; }

 private:
  static std::uint64_t nextSerial() {
    static std::atomic<std::uint64_t> next{1};
    return next++;
  }
  std::uint64_t serial_;
};

// One technique parameter, declared once beside the technique (pbrt-v4's Create(dict) model):
// the declaration gives the factory its value (default, range or choices checked), `--param`
// its checking, `penumbra list --params` its line and docs/cli.md its table row (tests/
// generated_tables_test.sh compares docs/cli.md with `penumbra list --params --format markdown`).
struct ParamSpec {
  enum class Type { Integer, Number, Boolean, Choice, Text };
  std::string key;
  Type type = Type::Number;
  double fallback = 0.0;             // Integer, Number, Boolean (0/1): the value when not given
  double lo = 0.0, hi = 0.0;         // Integer, Number: the accepted range
  std::vector<std::string> choices;  // Choice
  std::string text;                  // Choice, Text: the value when not given
  std::string shownDefault;          // when the default is a rule, not a value ("auto", "GL limit")
  std::string meaning;

  static ParamSpec integer(std::string key, int fallback, int lo, int hi, std::string meaning);
  static ParamSpec number(std::string key, double fallback, double lo, double hi, std::string meaning);
  static ParamSpec boolean(std::string key, bool fallback, std::string meaning);
  static ParamSpec choice(std::string key, std::string fallback, std::vector<std::string> choices, std::string meaning);
  static ParamSpec path(std::string key, std::string meaning);  // Text, empty by default
  // The same parameter with another default (a preset: pcss-ultra's samples).
  ParamSpec withDefault(double value) const;
  ParamSpec withDefault(std::string value) const;
  // The default as a rule, for lists and docs/cli.md ("auto", "eq. 3").
  ParamSpec shown(std::string rule) const;
  std::string defaultText() const;  // the shown rule or the value
  std::string rangeText() const;    // "[16, 16384]", "0/1", "exact|naive|lut", "path"
};

// Parameters of techniques from the command line (`--param key=value`, repeatable). One set is
// shared by every technique of a run: each technique reads the keys it declares (reads record
// them as known and consumed); `checkConsumed` then refuses a key no technique read, naming the
// keys that were known, so a misspelt parameter is never silently dropped. Values are converted
// and checked by the reader the scene loader uses too (core/key_values.h).
struct KeyPlace;  // core/key_values.h

class TechniqueParams {
 public:
  TechniqueParams() = default;
  // "key=value" strings; throws Error("param") for a malformed one or a repeated key. The
  // values of the `swept` keys come from a sweep: their errors name "sweep".
  explicit TechniqueParams(const std::vector<std::string>& keyValues, std::vector<std::string> swept = {});
  int integer(const ParamSpec& spec) const;
  double number(const ParamSpec& spec) const;
  bool boolean(const ParamSpec& spec) const;
  std::string text(const ParamSpec& spec) const;  // Choice (one of its choices) or Text
  bool empty() const { return values_.empty(); }
  // Throws Error("param") if a given key was read by no technique created with these params.
  void checkConsumed() const;
  // "key=value" of the given keys some technique created with these params read.
  std::vector<std::string> read() const;
  // The keys techniques created with these params asked for (given or not).
  const std::vector<std::string>& known() const { return known_; }
  // Counts `other`'s reads as reads of these params (one check over techniques created with
  // separate copies, e.g. one per technique and sweep preset).
  void noteReads(const TechniqueParams& other);

 private:
  const std::string* find(const std::string& key) const;
  std::string origin(const std::string& key) const;  // "param" or "sweep"
  KeyPlace place(const ParamSpec& spec) const;
  std::vector<std::pair<std::string, std::string>> values_;
  std::vector<std::string> swept_;
  mutable std::vector<std::string> known_, consumed_;
};

// The parameters as one technique reads them: the run's TechniqueParams through the
// technique's own declarations. Reading a key the technique does not declare is a programmer
// error (PENUMBRA_CHECK), so its declarations are all it reads.
class TechniqueArgs {
 public:
  TechniqueArgs(const TechniqueParams& given, const std::vector<ParamSpec>& declared, std::string technique)
      : given_(given), declared_(declared), technique_(std::move(technique)) {}
  int integer(const std::string& key) const { return given_.integer(spec(key)); }
  double number(const std::string& key) const { return given_.number(spec(key)); }
  bool boolean(const std::string& key) const { return given_.boolean(spec(key)); }
  std::string text(const std::string& key) const { return given_.text(spec(key)); }
  const ParamSpec& spec(const std::string& key) const;

 private:
  const TechniqueParams& given_;
  const std::vector<ParamSpec>& declared_;
  std::string technique_;
};

// The families the report colours and groups techniques by: how a technique finds
// visibility, not its code.
enum class TechniqueFamily {
  ExactPerSample,  // a result per light sample equal to ray tracing's (raytrace, dcs*)
  MultiView,       // a depth map per light sample (mvr*, vwss*, reproject*)
  SingleMap,       // one map from the light centre, filtered (pcss*, vssm*, msm*, evsm)
  Denoised,        // few rays per pixel, filtered in space and time (raytrace-denoised)
  Hard,            // unshadowed or hard shadows from the light centre (none, hard-sv)
};
inline constexpr TechniqueFamily kTechniqueFamilies[] = {TechniqueFamily::ExactPerSample, TechniqueFamily::MultiView,
                                                         TechniqueFamily::SingleMap, TechniqueFamily::Denoised,
                                                         TechniqueFamily::Hard};
const char* toString(TechniqueFamily f);

// A technique by name: what the table (techniques/registry.h) holds and what compare is handed.
struct TechniqueInfo {
  std::string name;
  std::string description;        // one line for `penumbra list`
  std::vector<ParamSpec> params;  // every parameter it reads, with its defaults
  std::function<std::unique_ptr<Technique>(const TechniqueArgs&)> create;
  TechniqueFamily family = TechniqueFamily::ExactPerSample;
  // create() with `given` read through this technique's declarations.
  std::unique_ptr<Technique> make(const TechniqueParams& given) const {
    return create(TechniqueArgs(given, params, name));
  }
};

// The table of techniques is a layer above: techniques/registry.h.

}  // namespace penumbra
