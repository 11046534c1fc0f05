#include "compare/compare.h"

#include <algorithm>
#include <optional>
#include <cctype>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"
#include "core/progress.h"

namespace penumbra {
namespace {

// Stacks images vertically (all the same width and channel count).
Image stack(const std::vector<const Image*>& images) {
  Image out(images.front()->width, 0, images.front()->channels);
  for (auto* im : images) {
    out.height += im->height;
    out.data.insert(out.data.end(), im->data.begin(), im->data.end());
  }
  return out;
}

template <class T>
std::vector<T> repeat(const std::vector<T>& v, std::size_t times) {
  std::vector<T> out;
  for (std::size_t i = 0; i < times; ++i) out.insert(out.end(), v.begin(), v.end());
  return out;
}

}  // namespace

TechniqueErrors measureErrors(const FrameResult& frame, const FrameResult& ref) {
  PENUMBRA_CHECK(frame.lights.size() == ref.lights.size(), "frames of different scenes");
  TechniqueErrors e;
  const auto& valid = ref.gbuffer.valid;
  std::size_t n = valid.size(), L = ref.lights.size();

  std::vector<const Image*> a, b;
  std::vector<std::uint8_t> band;
  std::vector<std::uint8_t> anyBand(n, 0);
  for (std::size_t l = 0; l < L; ++l) {
    a.push_back(&frame.lights[l].visibility);
    b.push_back(&ref.lights[l].visibility);
    auto m = edgeBandMask(ref.lights[l].visibility, 1);
    band.insert(band.end(), m.begin(), m.end());
    for (std::size_t i = 0; i < n; ++i) anyBand[i] |= m[i];
  }
  Image va = stack(a), vb = stack(b);
  auto validL = repeat(valid, L);
  e.visibility = compareImages(va, vb, {}, validL);
  std::vector<std::uint8_t> unshadowed(n * L, 0);
  for (std::size_t l = 0; l < L; ++l) {
    const auto& m = frame.lights[l].unshadowed;
    if (m.size() != n) continue;
    for (std::size_t i = 0; i < n; ++i)
      if (m[i] && valid[i]) unshadowed[l * n + i] = 1, ++e.unshadowedPixels;
  }
  e.visibilityExceptUnshadowed = e.unshadowedPixels ? compareImages(va, vb, unshadowed, validL) : e.visibility;
  e.visibilityOutsideBand = compareImages(va, vb, band, validL);
  e.shaded = compareImages(frame.color, ref.color, {}, valid);
  e.shadedOutsideBand = compareImages(frame.color, ref.color, anyBand, valid);

  std::int64_t agree = 0, pairs = 0;
  for (std::size_t l = 0; l < L; ++l) {
    const auto& fa = frame.lights[l];
    const auto& fb = ref.lights[l];
    float decision = 0.5f / float(std::max(1, fb.samples));
    for (std::size_t i = 0; i < n; ++i) {
      if (!valid[i] || band[l * n + i]) continue;
      float d = 0.0f;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(fa.visibility.data[i * 3 + c] - fb.visibility.data[i * 3 + c]));
      if (d > decision) ++e.misclassifiedPixels;
      if (fa.perSample.empty() || fb.perSample.empty() || fa.samples != fb.samples) continue;
      for (int k = 0; k < fb.samples; ++k) {
        std::size_t idx = i * std::size_t(fb.samples) + std::size_t(k);
        agree += std::abs(fa.perSample[idx] - fb.perSample[idx]) < 1e-3f;
        ++pairs;
      }
    }
  }
  if (pairs > 0) e.sampleAgreement = double(agree) / double(pairs);
  e.samplePairs = pairs;
  return e;
}

void writeFrame(const std::string& path, const FrameResult& frame, float exposure) {
  auto ext = std::filesystem::path(path).extension().string();
  if (ext == ".png") {
    writePng(path, frame.color, exposure);
  } else if (ext == ".exr") {
    std::vector<std::string> names;
    std::vector<ExrLayer> layers{{"", &frame.color}};
    for (std::size_t l = 0; l < frame.lights.size(); ++l)
      names.push_back(l == 0 ? "visibility" : "visibility" + std::to_string(l));
    for (std::size_t l = 0; l < frame.lights.size(); ++l) layers.push_back({names[l], &frame.lights[l].visibility});
    writeExr(path, layers);
  } else {
    throw Error(path, "output must end in .exr or .png");
  }
}

nlohmann::json frameSummary(const FrameResult& frame) {
  nlohmann::json stages = nlohmann::json::object(), harness = nlohmann::json::object(), counts = nlohmann::json::object();
  for (auto& s : frame.timer.stages()) {
    (s.kind == StageKind::Harness ? harness : stages)[s.stage] = s.ms;
    if (s.counted && s.kind == StageKind::Technique) counts[s.stage] = countsJson(s.counts);
  }
  nlohmann::json stats = nlohmann::json::object();
  for (auto& [k, v] : frame.statistics) stats[k] = v;
  nlohmann::json j = {{"stagesMs", stages}, {"statistics", stats}, {"totalMs", frame.timer.total()},
                      {"harnessStagesMs", harness}, {"harnessMs", frame.timer.harnessTotal()},
                      {"memoryBytes", frame.memoryBytes}, {"width", frame.color.width}, {"height", frame.color.height}};
  if (!counts.empty()) j["pipelineStatistics"] = counts;
  return j;
}

nlohmann::json countsJson(const PipelineCounts& c) {
  nlohmann::json j = nlohmann::json::object();
  for (auto& [k, v] : c.fields()) j[k] = v;
  return j;
}

PipelineCounts totalCounts(const CompareRun& run) {
  PipelineCounts sum;
  for (auto& [k, c] : run.counts) sum += c;
  return sum;
}

nlohmann::json errorsJson(const TechniqueErrors& e) {
  auto stats = [](const ErrorStats& s) {
    return nlohmann::json{{"rmse", s.rmse}, {"meanAbs", s.meanAbs}, {"maxAbs", s.maxAbs},
                          {"pixelsOver1_255", s.pixelsOver}, {"pixels", s.pixelsCounted}};
  };
  nlohmann::json j{{"visibility", stats(e.visibility)}, {"visibilityOutsideBand", stats(e.visibilityOutsideBand)},
                   {"shaded", stats(e.shaded)}, {"shadedOutsideBand", stats(e.shadedOutsideBand)},
                   {"misclassifiedPixelsOutsideBand", e.misclassifiedPixels},
                   {"unshadowedPixels", e.unshadowedPixels},
                   {"visibilityExceptUnshadowed", stats(e.visibilityExceptUnshadowed)}};
  if (e.sampleAgreement >= 0.0) j["sampleAgreementOutsideBand"] = e.sampleAgreement;
  return j;
}

// ---- insets ------------------------------------------------------------------------------

std::vector<Inset> chooseInsets(const FrameResult& ref, int count) {
  const int W = ref.color.width, H = ref.color.height;
  const int size = std::max(8, std::min(W, H) / 5);
  if (size > W || size > H) return {};
  // Penumbra pixels of any light, then a summed-area table for the window sums.
  std::vector<std::int64_t> sat(std::size_t(W + 1) * (H + 1), 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      int pen = 0;
      std::size_t i = std::size_t(y) * W + x;
      if (ref.gbuffer.valid.empty() || ref.gbuffer.valid[i])
        for (auto& l : ref.lights) {
          float v = l.visibility.data[i * 3];
          pen |= v > 0.02f && v < 0.98f;
        }
      sat[std::size_t(y + 1) * (W + 1) + x + 1] =
          pen + sat[std::size_t(y) * (W + 1) + x + 1] + sat[std::size_t(y + 1) * (W + 1) + x] - sat[std::size_t(y) * (W + 1) + x];
    }
  auto sum = [&](int x, int y) {
    auto at = [&](int xx, int yy) { return sat[std::size_t(yy) * (W + 1) + xx]; };
    return at(x + size, y + size) - at(x, y + size) - at(x + size, y) + at(x, y);
  };
  std::vector<Inset> out;
  const int step = std::max(1, size / 4);
  for (int n = 0; n < count; ++n) {
    std::int64_t best = 0;
    Inset pick;
    for (int y = 0; y + size <= H; y += step)
      for (int x = 0; x + size <= W; x += step) {
        bool overlaps = false;
        for (auto& o : out) overlaps |= x < o.x + o.w && o.x < x + size && y < o.y + o.h && o.y < y + size;
        std::int64_t s = overlaps ? -1 : sum(x, y);
        if (s > best) best = s, pick = {x, y, size, size};
      }
    if (best == 0) break;  // no (more) penumbra: no inset rather than an empty one
    out.push_back(pick);
  }
  return out;
}

SweepAxis SweepAxis::of(const std::string& key, const std::vector<int>& values) {
  SweepAxis axis{key, {}, values};
  for (int v : values) axis.values.push_back(std::to_string(v));
  return axis;
}

std::string ComparePreset::fileSuffix() const {
  if (values.empty()) return "";
  std::string s = "_";
  for (auto& [k, v] : values) {
    s += "_" + k + "-";
    for (char c : v) s += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '_';
  }
  return s;
}

bool CompareResult::hasConverged() const {
  for (auto& r : runs)
    if (r.converged) return true;
  return false;
}

bool CompareResult::hasTemporal() const {
  for (auto& r : runs)
    if (r.flicker >= 0.0) return true;
  return false;
}

namespace {

nlohmann::json spreadJson(const Spread& s) { return {{"median", s.median}, {"min", s.min}, {"max", s.max}}; }

// The presets: the cartesian product of the sweep axes, the first axis varying slowest.
std::vector<ComparePreset> makePresets(const RenderSettings& settings, const CompareOptions& o) {
  std::vector<ComparePreset> presets(1);
  presets[0].width = settings.width, presets[0].height = settings.height, presets[0].samples = settings.sampling.count;
  presets[0].params = o.params;
  std::vector<std::string> seen;
  for (auto& axis : o.sweeps) {
    if (std::find(seen.begin(), seen.end(), axis.key) != seen.end())
      throw Error("--sweep", "key '" + axis.key + "' swept twice", ExitCode::Usage);
    seen.push_back(axis.key);
    bool isParam = axis.key != "samples" && axis.key != "resolution";
    if (isParam)
      for (auto& p : o.params)
        if (p.rfind(axis.key + "=", 0) == 0)
          throw Error("--sweep", "key '" + axis.key + "' is given by --param too", ExitCode::Usage);
    std::vector<ComparePreset> next;
    for (auto& base : presets)
      for (auto& v : axis.values) {
        ComparePreset p = base;
        p.values.emplace_back(axis.key, v);
        const std::size_t i = std::size_t(&v - axis.values.data());
        if (!isParam && axis.integers.size() != axis.values.size())
          throw Error("compare", "sweep '" + axis.key + "' has no integer values (SweepAxis::of)");
        if (axis.key == "samples") {
          p.samples = axis.integers[i];
        } else if (axis.key == "resolution") {
          p.width = axis.integers[i];
          p.height = std::max(1, int(std::lround(double(p.width) * settings.height / settings.width)));
        } else {
          p.params.push_back(axis.key + "=" + v);
        }
        next.push_back(p);
      }
    presets = std::move(next);
  }
  for (auto& p : presets) {
    for (auto& [k, v] : p.values) p.label += (p.label.empty() ? "" : " ") + k + "=" + v;
  }
  return presets;
}

// What a technique renders at a preset: presets that differ only in parameters it does not
// read render the same thing and are measured once.
std::string renderKey(const ComparePreset& p, const std::vector<std::string>& read) {
  std::string key = fmt::format("{}x{} n{}", p.width, p.height, p.samples);
  for (auto& r : read) key += " " + r;
  return key;
}

// Visibility of every light stacked, and the surface mask, of one frame (for flicker).
struct FrameVisibility {
  std::vector<float> v;
  std::vector<std::uint8_t> valid;
};
FrameVisibility keepVisibility(const FrameResult& f) {
  FrameVisibility out;
  for (auto& l : f.lights) out.v.insert(out.v.end(), l.visibility.data.begin(), l.visibility.data.end());
  out.valid = f.gbuffer.valid;
  return out;
}

// RMS over frames f >= 1, surface pixels of both frames, lights and channels of
// (dA - dB) where d is the change from frame f-1 (dB omitted when `b` is null).
double temporalRms(const std::vector<FrameVisibility>& a, const std::vector<FrameVisibility>* b) {
  double sum = 0.0;
  std::int64_t count = 0;
  for (std::size_t f = 1; f < a.size(); ++f) {
    const std::size_t n = a[f].valid.size(), per = n * 3;
    for (std::size_t i = 0; i < a[f].v.size(); ++i) {
      std::size_t px = (i % per) / 3;
      if (!a[f].valid[px] || !a[f - 1].valid[px]) continue;
      double d = double(a[f].v[i]) - a[f - 1].v[i];
      if (b) d -= double((*b)[f].v[i]) - (*b)[f - 1].v[i];
      sum += d * d;
      ++count;
    }
  }
  return count ? std::sqrt(sum / double(count)) : 0.0;
}

// A crop of `im` scaled up by `zoom` (nearest), for insets.
Image crop(const Image& im, const Inset& r, int zoom) {
  Image out(r.w * zoom, r.h * zoom, im.channels);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < im.channels; ++c) out.at(x, y, c) = im.at(r.x + x / zoom, r.y + y / zoom, c);
  return out;
}

}  // namespace

CompareResult compareTechniques(gl::Context& context, const Scene& given, const RenderSettings& settings,
                                const CompareOptions& o) {
  namespace fs = std::filesystem;
  // Translated to the camera's frame once here, not by each technique's Renderer.
  std::optional<Scene> local;
  if (!given.isCameraRelative()) local.emplace(given).makeCameraRelative();
  const Scene& scene = local ? *local : given;
  CompareResult result;
  result.presets = makePresets(settings, o);
  const bool converged =
      o.converged || std::any_of(o.sweeps.begin(), o.sweeps.end(), [](auto& a) { return a.key == "samples"; });
  if (converged && !o.converged)
    PLOG_INFO("samples are swept: errors are also measured against {}", o.convergedReference.name);
  if (!o.reference.create || (converged && !o.convergedReference.create))
    throw Error("compare", "no reference technique was handed in (CompareOptions::reference, convergedReference)");
  const int frames = std::max(1, o.frames);
  const bool animated = scene.isAnimated();
  if (frames > 1 && !animated && std::all_of(scene.lights.begin(), scene.lights.end(), [](auto& l) { return l.emissionFrames.size() < 2; }))
    PLOG_WARN("--frames {}: the scene has no animation (no \"spin\", no animated light): every frame is the same", frames);

  // Every technique at every preset is created (and its parameters checked) before the long
  // renders start; presets that do not change what a technique renders are dropped.
  struct Job {
    const TechniqueInfo* technique;
    std::vector<std::string> read;
  };
  std::vector<std::vector<Job>> jobs(result.presets.size());
  {
    TechniqueParams all(result.presets[0].params);
    std::vector<std::string> keys;
    for (std::size_t p = 0; p < result.presets.size(); ++p)
      for (auto& info : o.techniques) {
        TechniqueParams params(result.presets[p].params);
        info.make(params);
        all.noteReads(params);
        std::string key = info.name + " " + renderKey(result.presets[p], params.read());
        if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
        keys.push_back(key);
        jobs[p].push_back({&info, params.read()});
      }
    all.checkConsumed();
  }
  if (!o.insets.empty()) {
    for (auto& r : o.insets)
      if (r.x + r.w > result.presets[0].width || r.y + r.h > result.presets[0].height)
        throw Error("--inset", fmt::format("{},{},{},{} is outside the {}x{} image", r.x, r.y, r.w, r.h,
                                           result.presets[0].width, result.presets[0].height), ExitCode::Usage);
  }
  if (!o.outDir.empty() && o.writeImages) fs::create_directories(fs::path(o.outDir) / "insets");

  int steps = 0;
  for (auto& j : jobs) steps += int(j.size()) + 1 + (converged ? 1 : 0);
  Progress progress(steps, o.progress);

  // Frame f: the scene posed at its time. Only moving scenes are copied, one frame at a time
  // (a long --frames run must not hold a copy of the scene per frame); a renderer made from a
  // posed scene is dropped before the next frame is posed.
  std::unique_ptr<Scene> posed;
  int posedFrame = -1;
  auto sceneAt = [&](int f) -> const Scene& {
    if (!animated) return scene;
    if (posedFrame != f) {
      posed = std::make_unique<Scene>(scene.posedAt(settings.time + float(f) / o.fps));
      posedFrame = f;
    }
    return *posed;
  };

  std::map<std::string, FrameResult> convergedRefs;  // by "WxH" (independent of the sample count)
  for (std::size_t pi = 0; pi < result.presets.size(); ++pi) {
    const ComparePreset& preset = result.presets[pi];
    RenderSettings s = settings;
    s.width = preset.width, s.height = preset.height, s.sampling.count = preset.samples;
    // A still has one renderer for every technique of the preset; --frames makes one per
    // frame and technique (building one is not timed: the G-buffer is drawn in render()).
    std::unique_ptr<Renderer> still;
    if (frames == 1) still = std::make_unique<Renderer>(context, sceneAt(0), s);
    // `slot` keeps the renderer of the last frame asked for, so warm-up and timed renders of one
    // frame share it.
    struct Slot {
      std::unique_ptr<Renderer> renderer;
      int frame = -1;
    };
    auto rendererFor = [&](int f, ShadingMode shading, Slot& slot) -> Renderer& {
      if (frames == 1 && shading == s.shading) return *still;
      if (slot.renderer && slot.frame == f) return *slot.renderer;
      slot.renderer.reset();  // before sceneAt replaces the scene it refers to
      RenderSettings sf = s;
      sf.shading = shading;
      sf.time = settings.time + float(f) / o.fps;
      slot.renderer = std::make_unique<Renderer>(context, sceneAt(f), sf);
      slot.frame = f;
      return *slot.renderer;
    };
    const std::string suffix = preset.fileSuffix();
    const std::string at = preset.label.empty() ? "" : " @ " + preset.label;

    // Renders `tech` at every frame (timed frames at frame 0 for stills, one timed render per
    // frame otherwise) and fills the timing fields of `run`; returns frame 0 and, for
    // --frames, every frame's visibility.
    auto renderRun = [&](Technique& tech, CompareRun& run, ShadingMode shading,
                         std::vector<FrameVisibility>* keep) -> FrameResult {
      Slot slot;
      run.shading = toString(shading);
      FrameResult first;
      // A still: the same frame timed on one renderer. --frames: frame i on its own renderer
      // (warm-up frames are frame 0), every frame's visibility kept for flicker.
      Timing t = timeRenders(
          frames == 1 ? o.timingFrames : frames, o.warmup,
          [&](int i) { return rendererFor(i, shading, slot).render(tech, run.technique); },
          [&](int i, const FrameResult& fr) {
            if (keep) keep->push_back(keepVisibility(fr));
            if (frames > 1 && i == 0) first = fr;
          });
      for (auto& [k, v] : t.stages) run.stages.emplace_back(k, v);
      for (auto& [k, v] : t.harnessStages) run.harnessStages.emplace_back(k, v);
      for (auto& st : t.last.timer.stages())
        if (st.counted && st.kind == StageKind::Technique && st.stage != "prepare") run.counts.emplace_back(st.stage, st.counts);
      run.total = t.total, run.harness = t.harness, run.prepareMs = t.prepareMs;
      if (frames == 1) first = std::move(t.last);
      run.memoryBytes = first.memoryBytes, run.statistics = first.statistics;
      return first;
    };

    // Writes frame 0's images and insets; `against` is the reference of the heat map.
    auto writeImages = [&](const std::string& base, const FrameResult& f, const FrameResult* against, CompareRun& run) {
      if (o.outDir.empty()) return;
      fs::path dir(o.outDir);
      if (o.writeExr) writeFrame((dir / (base + ".exr")).string(), f);
      if (!o.writeImages) return;
      writeFrame((dir / (base + ".png")).string(), f);
      run.image = base + ".png";
      if (against) {
        writePng((dir / (base + "_heat.png")).string(),
                 errorHeatMap(f.lights[0].visibility, against->lights[0].visibility, 0.25f));
        run.heat = base + "_heat.png";
      }
      // Pixels left unshadowed by design (outside the shadow maps' frustum), white on black.
      std::vector<std::uint8_t> any(f.gbuffer.valid.size(), 0);
      bool some = false;
      for (const auto& l : f.lights)
        for (std::size_t i = 0; i < l.unshadowed.size() && i < any.size(); ++i) some |= (any[i] |= l.unshadowed[i]) != 0;
      if (some) {
        Image mask(f.color.width, f.color.height, 3);
        for (std::size_t i = 0; i < any.size(); ++i)
          for (int c = 0; c < 3; ++c) mask.data[i * 3 + std::size_t(c)] = any[i] ? 1.0f : 0.0f;
        writePng((dir / (base + "_unshadowed.png")).string(), mask);
        run.unshadowedMask = base + "_unshadowed.png";
      }
      if (pi != 0) return;
      for (std::size_t i = 0; i < result.insets.size(); ++i) {
        const Inset& r = result.insets[i];
        int zoom = std::max(1, 160 / std::max(r.w, r.h));
        std::string name = fmt::format("insets/{}_{}.png", base, i);
        writePng((dir / name).string(), crop(f.color, r, zoom));
        run.insetImages.push_back(name);
      }
    };

    // References: raytrace with this preset's samples; raytrace-converged once per size.
    progress.step("reference: " + o.reference.name + at);
    CompareRun refRun;
    refRun.technique = o.reference.name, refRun.preset = pi, refRun.reference = true;
    std::vector<FrameVisibility> refFrames;
    auto refTech = o.reference.make(TechniqueParams{});
    FrameResult ref;
    try {
      ref = renderRun(*refTech, refRun, s.shading, frames > 1 ? &refFrames : nullptr);
    } catch (const Error& e) {  // nothing can be measured without it: the comparison ends
      throw Error("compare", "the reference (" + o.reference.name + at + ") failed: " + e.what(), e.exitCode());
    }
    if (pi == 0) {
      result.insets = o.insets.empty() ? chooseInsets(ref) : o.insets;
      result.insetSource = o.insets.empty() ? "chosen" : "given";
    }
    const FrameResult* conv = nullptr;
    if (converged) {
      std::string key = fmt::format("{}x{}", s.width, s.height);
      progress.step("reference: " + o.convergedReference.name + at);
      if (!convergedRefs.count(key)) {
        auto t = o.convergedReference.make(TechniqueParams{});
        Slot slot;
        convergedRefs[key] = rendererFor(0, s.shading, slot).render(*t);
        if (!o.outDir.empty() && o.writeExr)
          writeFrame((fs::path(o.outDir) / (o.convergedReference.name + "_" + key + ".exr")).string(), convergedRefs[key]);
      }
      conv = &convergedRefs[key];
      refRun.converged = measureErrors(ref, *conv);
    }
    refRun.errors = measureErrors(ref, ref);
    writeImages(o.reference.name + suffix, ref, conv, refRun);
    result.runs.push_back(std::move(refRun));

    for (auto& job : jobs[pi]) {
      const std::string& name = job.technique->name;
      progress.step(name + at);
      CompareRun run;
      run.technique = name, run.preset = pi, run.params = job.read;
      std::vector<FrameVisibility> kept;
      FrameResult f;
      try {
        TechniqueParams params(preset.params);
        auto tech = job.technique->make(params);
        ShadingMode shading = s.shading;
        if (shading == ShadingMode::PerSample && !tech->providesPerSample()) shading = ShadingMode::Modulate;
        f = renderRun(*tech, run, shading, frames > 1 ? &kept : nullptr);
        // (its render targets go, at the end of this block, before the next technique allocates its own)
      } catch (const std::exception& e) {
        // One technique's failure is its row of the report, not the end of the comparison.
        CompareRun failed;
        failed.technique = name, failed.preset = pi, failed.params = job.read;
        failed.shading = run.shading;
        failed.failed = true;
        failed.failure = e.what();
        PLOG_ERROR("{}{} failed: {}", name, at, failed.failure);
        result.runs.push_back(std::move(failed));
        continue;
      }
      run.errors = measureErrors(f, ref);
      if (conv) run.converged = measureErrors(f, *conv);
      if (frames > 1) {
        run.flicker = temporalRms(kept, &refFrames);
        run.referenceMotion = temporalRms(refFrames, nullptr);
        // Mean visibility RMSE over the frames, surface pixels of the reference.
        double sum = 0.0;
        for (std::size_t k = 0; k < kept.size(); ++k) {
          double e = 0.0;
          std::int64_t n = 0;
          const std::size_t per = refFrames[k].valid.size() * 3;
          for (std::size_t i = 0; i < kept[k].v.size(); ++i) {
            if (!refFrames[k].valid[(i % per) / 3]) continue;
            double d = double(kept[k].v[i]) - refFrames[k].v[i];
            e += d * d, ++n;
          }
          sum += n ? std::sqrt(e / double(n)) : 0.0;
        }
        run.meanFrameRmse = sum / double(kept.size());
      }
      writeImages(name + suffix, f, conv ? conv : &ref, run);
      result.runs.push_back(std::move(run));
    }
  }
  progress.finish();

  auto& j = result.info;
  j["scene"] = scene.sourcePath.empty() ? "default" : scene.sourcePath;
  j["sceneName"] = scene.name;
  j["renderer"] = context.renderer();
  j["pipelineStatistics"] = !settings.pipelineStatistics ? "not counted (RenderSettings::pipelineStatistics off)"
                            : gl::PipelineStatistics::supported()
                                ? "counted per stage (ARB_pipeline_statistics_query)"
                                : "not counted: " + context.renderer() + " has no ARB_pipeline_statistics_query";
  j["glVersion"] = context.version();
  {
    std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    j["date"] = date;
  }
  j["width"] = settings.width;
  j["height"] = settings.height;
  j["samples"] = settings.sampling.count;
  j["strategy"] = toString(settings.sampling.strategy);
  j["pattern"] = toString(settings.sampling.pattern);
  j["seed"] = settings.sampling.seed;
  j["shading"] = toString(settings.shading);
  j["time"] = settings.time;
  j["triangles"] = scene.triangleCount();
  j["lights"] = scene.lights.size();
  j["params"] = o.params;
  j["timingFrames"] = o.timingFrames;
  j["warmupFrames"] = o.warmup;
  j["frames"] = frames;
  if (frames > 1) j["fps"] = o.fps;
  nlohmann::json sweeps = nlohmann::json::array();
  for (auto& a : o.sweeps) sweeps.push_back({{"key", a.key}, {"values", a.values}});
  j["sweeps"] = sweeps;
  j["convergedReference"] = converged;
  return result;
}

nlohmann::json CompareResult::json() const {
  nlohmann::json j = info;
  nlohmann::json presetsJson = nlohmann::json::array();
  for (auto& p : presets)
    presetsJson.push_back({{"label", p.label}, {"width", p.width}, {"height", p.height}, {"samples", p.samples},
                           {"params", p.params}});
  j["presets"] = presetsJson;
  nlohmann::json insetJson = nlohmann::json::array();
  for (auto& r : insets) insetJson.push_back({r.x, r.y, r.w, r.h});
  j["insets"] = insetJson;
  j["insetSource"] = insetSource;
  nlohmann::json runsJson = nlohmann::json::array();
  for (auto& r : runs) {
    nlohmann::json stages = nlohmann::json::object(), spreads = nlohmann::json::object(), stats = nlohmann::json::object();
    for (auto& [k, v] : r.stages) stages[k] = v.median, spreads[k] = spreadJson(v);
    for (auto& [k, v] : r.statistics) stats[k] = v;
    nlohmann::json harness = nlohmann::json::object();
    for (auto& [k, v] : r.harnessStages) harness[k] = v.median;
    nlohmann::json t{{"name", r.technique},
                     {"preset", presets[r.preset].label},
                     {"presetIndex", r.preset},
                     {"reference", r.reference},
                     {"params", r.params},
                     {"samples", presets[r.preset].samples},
                     {"width", presets[r.preset].width},
                     {"height", presets[r.preset].height},
                     {"shading", r.shading},
                     {"stagesMs", stages},
                     {"stagesSpreadMs", spreads},
                     {"totalMs", r.total.median},
                     {"totalSpreadMs", spreadJson(r.total)},
                     {"harnessStagesMs", harness},
                     {"harnessMs", r.harness.median},
                     {"harnessSpreadMs", spreadJson(r.harness)},
                     {"prepareMs", r.prepareMs},
                     {"memoryBytes", r.memoryBytes},
                     {"statistics", stats},
                     {"errors", errorsJson(r.errors)},
                     {"image", r.image},
                     {"heat", r.heat},
                     {"unshadowedMask", r.unshadowedMask},
                     {"insets", r.insetImages},
                     {"status", r.failed ? "failed" : "ok"}};
    if (r.failed) {
      // No numbers for a failed run: its timings and errors were never measured.
      for (const char* k : {"stagesMs", "stagesSpreadMs", "totalMs", "totalSpreadMs", "prepareMs", "memoryBytes",
                            "statistics", "errors", "harnessStagesMs", "harnessMs", "harnessSpreadMs"})
        t.erase(k);
      t["error"] = r.failure;
    }
    if (!r.failed && !r.counts.empty()) {
      nlohmann::json counts = nlohmann::json::object();
      for (auto& [k, c] : r.counts) counts[k] = countsJson(c);
      t["pipelineStatistics"] = {{"stages", counts}, {"total", countsJson(totalCounts(r))}};
    }
    if (r.converged) t["convergedErrors"] = errorsJson(*r.converged);
    if (r.flicker >= 0.0)
      t["temporal"] = {{"flicker", r.flicker}, {"referenceMotion", r.referenceMotion}, {"meanVisibilityRmse", r.meanFrameRmse}};
    runsJson.push_back(t);
  }
  j["runs"] = runsJson;
  return j;
}

}  // namespace penumbra
