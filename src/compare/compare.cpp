#include "compare/compare.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "core/error.h"
#include "core/log.h"
#include "core/progress.h"

namespace penumbra {

PipelineCounts totalCounts(const CompareRun& run) {
  PipelineCounts sum;
  for (auto& [k, c] : run.counts) sum += c;
  return sum;
}

const char* toString(ErrorAxis a) {
  switch (a) {
    case ErrorAxis::Visibility:
      return "visibility";
    case ErrorAxis::Shaded:
      return "shaded";
    case ErrorAxis::Flip:
      return "flip";
  }
  return "?";
}

double CompareRun::errorOn(ErrorAxis axis) const {
  switch (axis) {
    case ErrorAxis::Visibility:
      return plotError();
    case ErrorAxis::Shaded:
      return converged ? converged->shaded.rmse : errors.shaded.rmse;
    case ErrorAxis::Flip:
      return flip ? *flip : -1.0;
  }
  return -1.0;
}

std::vector<std::pair<const ComparePreset*, double>> referenceNoiseOn(const CompareResult& r, ErrorAxis axis) {
  std::vector<std::pair<const ComparePreset*, double>> out;
  if (axis == ErrorAxis::Flip) return out;
  for (const CompareRun& run : r.runs) {
    if (!run.referenceNoise) continue;
    const double v = axis == ErrorAxis::Visibility ? run.referenceNoise->visibility : run.referenceNoise->shaded;
    const ComparePreset& p = r.presets[run.preset];
    if (std::none_of(out.begin(), out.end(),
                     [&](auto& o) { return o.first->width == p.width && o.first->height == p.height; }))
      out.emplace_back(&p, v);
  }
  return out;
}

bool CompareResult::hasConverged() const {
  return std::any_of(runs.begin(), runs.end(), [](auto& r) { return r.converged.has_value(); });
}

bool CompareResult::hasFlip() const {
  return std::any_of(runs.begin(), runs.end(), [](auto& r) { return r.flip.has_value(); });
}

bool CompareResult::hasTemporal() const {
  return std::any_of(runs.begin(), runs.end(), [](auto& r) { return r.flicker >= 0.0; });
}

namespace {

struct Job {
  const TechniqueInfo* technique;
  std::vector<std::string> read;  // the parameters it read at this preset
};

// What a comparison will render: the presets, whether the converged reference is measured, and
// per preset the techniques, every one created with its parameters (a key no technique reads is
// refused; presets that do not change what a technique renders are dropped). No GL.
struct Plan {
  std::vector<ComparePreset> presets;
  bool converged = false;
  std::vector<std::vector<Job>> jobs;  // per preset
};

Plan planComparison(const RenderSettings& settings, const CompareOptions& o) {
  Plan plan;
  plan.presets = makePresets(settings, o.params, o.sweeps);
  plan.converged =
      o.converged || std::any_of(o.sweeps.begin(), o.sweeps.end(), [](auto& a) { return a.key == "samples"; });
  if (!o.reference.create || (plan.converged && !o.convergedReference.create && !o.givenConverged))
    throw Error("compare", "no reference technique was handed in (CompareOptions::reference, convergedReference)");
  if ((o.givenReference || o.givenConverged) && (plan.presets.size() != 1 || o.frames > 1))
    throw Error("compare", "references rendered elsewhere are for one preset and one frame", ExitCode::Usage);
  for (auto& r : o.insets)
    if (r.x + r.w > plan.presets[0].width || r.y + r.h > plan.presets[0].height)
      throw Error("compare",
                  fmt::format("inset {},{},{},{} is outside the {}x{} image", r.x, r.y, r.w, r.h, plan.presets[0].width,
                              plan.presets[0].height),
                  ExitCode::Usage);
  plan.jobs.resize(plan.presets.size());
  TechniqueParams all(plan.presets[0].params, plan.presets[0].swept);
  std::vector<std::string> keys;
  for (std::size_t p = 0; p < plan.presets.size(); ++p)
    for (auto& info : o.techniques) {
      TechniqueParams params(plan.presets[p].params, plan.presets[p].swept);
      info.make(params);
      all.noteReads(params);
      std::string key = info.name + " " + renderKey(plan.presets[p], params.read());
      if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
      keys.push_back(key);
      plan.jobs[p].push_back({&info, params.read()});
    }
  // The converged reference reads its own parameters (`reference-*`) from the same set.
  if (plan.converged)
    for (auto& preset : plan.presets) {
      TechniqueParams params(preset.params, preset.swept);
      o.convergedReference.make(params);
      all.noteReads(params);
    }
  all.checkConsumed();
  return plan;
}

// One call of compareTechniques: the plan (every technique at every preset, created and its
// parameters checked before the long renders start), then per preset the references and the
// techniques, each rendered, timed, measured and written.
class Comparison {
 public:
  Comparison(gl::Context& context, const Scene& scene, const RenderSettings& settings, const CompareOptions& o)
      : context_(context),
        scene_(scene),
        settings_(settings),
        o_(o),
        frames_(std::max(1, o.frames)),
        animated_(scene.isAnimated()) {
    Plan plan = planComparison(settings, o);
    result_.presets = std::move(plan.presets);
    converged_ = plan.converged;
    jobs_ = std::move(plan.jobs);
    if (converged_ && !o.converged)
      PLOG_INFO("samples are swept: errors are also measured against {}", o.convergedReference.name);
    if (frames_ > 1 && !animated_ &&
        std::all_of(scene.lights.begin(), scene.lights.end(), [](auto& l) { return l.emissionFrames.size() < 2; }))
      PLOG_WARN("{} frames: the scene has no animation (no \"spin\", no animated light): every frame is the same",
                frames_);
  }

  CompareResult run() {
    if (!o_.outDir.empty() && o_.writeImages)
      std::filesystem::create_directories(std::filesystem::path(o_.outDir) / "insets");
    int steps = 0;
    for (auto& j : jobs_) steps += int(j.size()) + 1 + (converged_ ? 1 : 0);
    Progress progress(steps, o_.progress);
    rows_ = 0;
    for (auto& j : jobs_) rows_ += j.size() + (o_.givenReference ? 0 : 1);  // each preset's reference and techniques
    for (std::size_t p = 0; p < result_.presets.size(); ++p) runPreset(p, progress);
    progress.finish();
    result_.info = info();
    return std::move(result_);
  }

 private:
  // The renderer of the last frame asked for, so warm-up and timed renders of one frame share it.
  struct Slot {
    std::unique_ptr<Renderer> renderer;
    int frame = -1;
  };
  // A reference's frames: frame 0, every frame's visibility under --frames, and the converged
  // reference of its size (or null).
  struct References {
    FrameResult frame;
    std::vector<FrameVisibility> frames;
    const FrameResult* converged = nullptr;
    // FLIP's reference side for the techniques' shaded images: the converged reference's, or
    // without it the same-sample reference's.
    std::unique_ptr<HdrFlipReference> flip;
  };

  // Frame f: the scene posed at its time. Only moving scenes are copied, one frame at a time (a
  // long --frames run must not hold a copy of the scene per frame); a renderer made from a posed
  // scene is dropped before the next frame is posed.
  const Scene& sceneAt(int f) {
    if (!animated_) return scene_;
    if (posedFrame_ != f) {
      posed_ = std::make_unique<Scene>(scene_.posedAt(settings_.time + float(f) / o_.fps));
      posedFrame_ = f;
    }
    return *posed_;
  }

  // A still has one renderer for every technique of the preset; --frames makes one per frame
  // and technique (building one is not timed: the G-buffer is drawn in render()).
  Renderer& rendererFor(int f, ShadingMode shading, Slot& slot) {
    if (frames_ == 1 && shading == preset_.shading) return *still_;
    if (slot.renderer && slot.frame == f) return *slot.renderer;
    slot.renderer.reset();  // before sceneAt replaces the scene it refers to
    RenderSettings sf = preset_;
    sf.shading = shading;
    sf.time = settings_.time + float(f) / o_.fps;
    slot.renderer = std::make_unique<Renderer>(context_, sceneAt(f), sf);
    slot.frame = f;
    return *slot.renderer;
  }

  // Renders `tech` (a still: the timed frames on one renderer; --frames: frame i on its own
  // renderer, warm-up frames at frame 0, every frame's visibility kept in `keep`), fills the
  // timing fields of `run` and returns frame 0.
  FrameResult renderRun(Technique& tech, CompareRun& run, ShadingMode shading, std::vector<FrameVisibility>* keep) {
    Slot slot;
    run.shading = toString(shading);
    FrameResult first;
    Timing t = timeRenders(
        frames_ == 1 ? o_.timingFrames : frames_, o_.warmup,
        [&](int i) { return rendererFor(i, shading, slot).render(tech, run.technique); },
        [&](int i, const FrameResult& fr) {
          if (keep) keep->push_back(keepVisibility(fr));
          if (frames_ > 1 && i == 0) first = fr;
        });
    for (auto& [k, v] : t.stages) run.stages.emplace_back(k, v);
    for (auto& [k, v] : t.harnessStages) run.harnessStages.emplace_back(k, v);
    for (auto& st : t.last.timer.stages())
      if (st.counted && st.kind == StageKind::Technique && st.stage != "prepare")
        run.counts.emplace_back(st.stage, st.counts);
    run.total = t.total, run.harness = t.harness, run.prepareMs = t.prepareMs;
    if (frames_ == 1) first = std::move(t.last);
    run.memoryBytes = first.memoryBytes, run.statistics = first.statistics, run.notes = first.notes;
    return first;
  }

  void writeImages(const std::string& base, const FrameResult& f, const FrameResult* against, const Image* flip,
                   CompareRun& run) {
    if (o_.outDir.empty()) return;
    writeRunImages({o_.outDir, o_.writeExr, o_.writeImages, presetIndex_ == 0 ? result_.insets : std::vector<Inset>{}},
                   base + result_.presets[presetIndex_].fileSuffix(), f, against, flip, run);
  }

  // The shaded image's HDR-FLIP against the references' (CompareRun::flip): its mean over
  // surface pixels into `run`, the map returned for the heat map.
  static Image measureFlip(const FrameResult& f, const References& refs, CompareRun& run) {
    Image map = refs.flip->against(f.color);
    run.flip = meanOf(map, (refs.converged ? *refs.converged : refs.frame).gbuffer.valid);
    return map;
  }

  std::string at() const {
    const std::string& label = result_.presets[presetIndex_].label;
    return label.empty() ? "" : " @ " + label;
  }

  // raytrace with this preset's samples; raytrace-converged once per image size. Nothing can be
  // measured without them: a failure ends the comparison.
  References renderReferences(Progress& progress) {
    References refs;
    CompareRun run;
    run.technique = o_.reference.name, run.preset = presetIndex_, run.reference = true;
    run.family = o_.reference.family;
    if (o_.givenReference) {
      refs.frame = *o_.givenReference;
    } else {
      progress.step("reference: " + o_.reference.name + at());
      auto tech = o_.reference.make(TechniqueParams{});
      try {
        refs.frame = renderRun(*tech, run, preset_.shading, frames_ > 1 ? &refs.frames : nullptr);
      } catch (const Error& e) {
        throw Error("compare", "the reference (" + o_.reference.name + at() + ") failed: " + e.what(), e.exitCode());
      }
      if (o_.onReference) o_.onReference(refs.frame);
    }
    if (presetIndex_ == 0) {
      result_.insets = o_.insets.empty() ? chooseInsets(refs.frame) : o_.insets;
      result_.insetSource = o_.insets.empty() ? "chosen" : "given";
    }
    if (converged_) {
      refs.converged = o_.givenConverged ? o_.givenConverged : &renderConverged(progress);
      run.converged = measureErrors(refs.frame, *refs.converged);
      run.referenceNoise = referenceNoise(*refs.converged);
      run.referenceStatistics = refs.converged->statistics;
      if (!run.referenceNoise)
        PLOG_WARN("{}{} states no noise: the report shows no error floor", o_.convergedReference.name, at());
    }
    refs.flip =
        std::make_unique<HdrFlipReference>((refs.converged ? *refs.converged : refs.frame).color, o_.pixelsPerDegree);
    if (o_.givenReference) return refs;  // its row is the run's that rendered it
    run.errors = measureErrors(refs.frame, refs.frame);
    Image flip;
    if (refs.converged) flip = measureFlip(refs.frame, refs, run);
    writeImages(o_.reference.name, refs.frame, refs.converged, refs.converged ? &flip : nullptr, run);
    result_.runs.push_back(std::move(run));
    rowDone();
    return refs;
  }

  // raytrace-converged of this preset's image size (and reference-* parameters, should a sweep
  // vary them), rendered once.
  const FrameResult& renderConverged(Progress& progress) {
    TechniqueParams params(result_.presets[presetIndex_].params, result_.presets[presetIndex_].swept);
    auto conv = o_.convergedReference.make(params);
    std::string key = fmt::format("{}x{}", preset_.width, preset_.height);
    const std::string file = key + (params.read().empty() ? "" : fmt::format("_{}", convergedRefs_.size()));
    for (auto& r : params.read()) key += " " + r;
    progress.step("reference: " + o_.convergedReference.name + at());
    if (!convergedRefs_.count(key)) {
      Slot slot;
      convergedRefs_[key] = rendererFor(0, preset_.shading, slot).render(*conv);
      if (!o_.outDir.empty() && o_.writeExr)
        writeFrame((std::filesystem::path(o_.outDir) / (o_.convergedReference.name + "_" + file + ".exr")).string(),
                   convergedRefs_[key]);
    }
    return convergedRefs_[key];
  }

  // One technique's run; its failure (an Error or another exception while it was created or
  // rendered) is its row of the report, not the end of the comparison.
  void renderTechnique(const Job& job, const References& refs) {
    CompareRun run;
    run.technique = job.technique->name, run.preset = presetIndex_, run.params = job.read;
    run.family = job.technique->family;
    std::vector<FrameVisibility> kept;
    FrameResult f;
    try {
      TechniqueParams params(result_.presets[presetIndex_].params, result_.presets[presetIndex_].swept);
      auto tech = job.technique->make(params);
      ShadingMode shading = preset_.shading;
      if (shading == ShadingMode::PerSample && !tech->providesPerSample()) shading = ShadingMode::Modulate;
      f = renderRun(*tech, run, shading, frames_ > 1 ? &kept : nullptr);
      // (its render targets go here, before the next technique allocates its own)
    } catch (const std::exception& e) {
      CompareRun failed;
      failed.technique = run.technique, failed.preset = presetIndex_, failed.params = job.read;
      failed.family = run.family;
      failed.shading = run.shading;
      failed.failed = true;
      failed.failure = e.what();
      PLOG_ERROR("{}{} failed: {}", run.technique, at(), failed.failure);
      result_.runs.push_back(std::move(failed));
      rowDone();
      return;
    }
    run.errors = measureErrors(f, refs.frame);
    if (refs.converged) run.converged = measureErrors(f, *refs.converged);
    if (frames_ > 1) {
      const TemporalErrors t = measureTemporal(kept, refs.frames);
      run.flicker = t.flicker, run.referenceMotion = t.referenceMotion, run.meanFrameRmse = t.meanFrameRmse;
    }
    const Image flip = measureFlip(f, refs, run);
    writeImages(run.technique, f, refs.converged ? refs.converged : &refs.frame, &flip, run);
    result_.runs.push_back(std::move(run));
    rowDone();
  }

  // CompareOptions::onRow: the result so far, marked incomplete.
  void rowDone() {
    if (!o_.onRow) return;
    CompareResult partial = result_;
    partial.info = info();
    partial.info["incomplete"] = fmt::format("{} of {} rows", partial.runs.size(), rows_);
    o_.onRow(partial);
  }

  void runPreset(std::size_t p, Progress& progress) {
    const ComparePreset& preset = result_.presets[p];
    presetIndex_ = p;
    preset_ = settings_;
    preset_.width = preset.width, preset_.height = preset.height, preset_.sampling.count = preset.samples;
    still_.reset();
    if (frames_ == 1) still_ = std::make_unique<Renderer>(context_, sceneAt(0), preset_);
    const References refs = renderReferences(progress);
    for (auto& job : jobs_[p]) {
      progress.step(job.technique->name + at());
      renderTechnique(job, refs);
    }
  }

  nlohmann::json info() const {
    nlohmann::json j;
    j["scene"] = scene_.sourcePath.empty() ? "default" : scene_.sourcePath;
    j["sceneName"] = scene_.name;
    j["renderer"] = context_.renderer();
    j["pipelineStatistics"] = !settings_.pipelineStatistics ? "not counted (RenderSettings::pipelineStatistics off)"
                              : gl::PipelineStatistics::supported()
                                  ? "counted per stage (ARB_pipeline_statistics_query)"
                                  : "not counted: " + context_.renderer() + " has no ARB_pipeline_statistics_query";
    j["glVersion"] = context_.version();
    j["date"] = utcNow();
    j["width"] = settings_.width;
    j["height"] = settings_.height;
    j["samples"] = settings_.sampling.count;
    j["strategy"] = toString(settings_.sampling.strategy);
    j["pattern"] = toString(settings_.sampling.pattern);
    j["seed"] = settings_.sampling.seed;
    j["shading"] = toString(settings_.shading);
    j["time"] = settings_.time;
    j["triangles"] = scene_.triangleCount();
    j["lights"] = scene_.lights.size();
    j["params"] = o_.params;
    j["timingFrames"] = o_.timingFrames;
    j["warmupFrames"] = o_.warmup;
    j["frames"] = frames_;
    if (frames_ > 1) j["fps"] = o_.fps;
    nlohmann::json sweeps = nlohmann::json::array();
    for (auto& a : o_.sweeps) sweeps.push_back({{"key", a.key}, {"values", a.values}});
    j["sweeps"] = sweeps;
    j["convergedReference"] = converged_;
    j["flipPixelsPerDegree"] = o_.pixelsPerDegree;
    return j;
  }

  gl::Context& context_;
  const Scene& scene_;
  const RenderSettings settings_;
  const CompareOptions& o_;
  const int frames_;
  const bool animated_;
  bool converged_ = false;
  CompareResult result_;
  std::vector<std::vector<Job>> jobs_;  // per preset
  std::unique_ptr<Scene> posed_;
  int posedFrame_ = -1;
  std::map<std::string, FrameResult> convergedRefs_;  // by "WxH" (independent of the sample count)
  // The preset being rendered: its index, its settings and (a still) its renderer.
  std::size_t presetIndex_ = 0;
  std::size_t rows_ = 0;  // the run's rows: each preset's reference and techniques
  RenderSettings preset_;
  std::unique_ptr<Renderer> still_;
};

}  // namespace

void checkComparison(const RenderSettings& settings, const CompareOptions& options) {
  planComparison(settings, options);
}

CompareResult compareTechniques(gl::Context& context, const Scene& given, const RenderSettings& settings,
                                const CompareOptions& o) {
  // Translated to the camera's frame once here, not by each technique's Renderer.
  std::optional<Scene> local;
  if (!given.isCameraRelative()) local.emplace(given).makeCameraRelative();
  return Comparison(context, local ? *local : given, settings, o).run();
}

}  // namespace penumbra
