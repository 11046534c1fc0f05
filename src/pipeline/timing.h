// Timing a technique's frames on one renderer, shared by `compare` and the benchmarks: warm-up
// frames first, then the median and spread of each stage. Stages are timed with glFinish and
// a steady clock (StageTimer), as GL timer queries are not meaningful on llvmpipe. A frame's
// total is the technique's stages (G-buffer, its visibility passes, shading); the harness's
// readbacks and uploads (StageKind::Harness) are timed apart, as `harness`.
#pragma once

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "pipeline/renderer.h"

namespace penumbra {

struct Spread {
  double median = 0, min = 0, max = 0;
};

inline Spread spread(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  std::size_t n = v.size();
  if (n == 0) return {};
  double med = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {med, v.front(), v.back()};
}

struct Timing {
  std::map<std::string, Spread> stages;  // "prepare" (once per scene) left out
  Spread total;                          // of `stages`
  std::map<std::string, Spread> harnessStages;
  Spread harness;          // of `harnessStages`
  double prepareMs = 0.0;  // the once-per-scene stage (the longest seen)
  FrameResult last;        // the last timed frame
  // The median of a stage the timed frames recorded. A name they did not record is an error
  // naming the ones they did (a renamed stage must not read as 0 ms in a benchmark's table); a
  // caller whose configuration skips a stage leaves it out instead of reading it.
  double stage(const std::string& name) const {
    auto it = stages.find(name);
    if (it == stages.end()) {
      std::string known;
      for (auto& [k, v] : stages) known += (known.empty() ? "" : ", ") + k;
      throw Error("timing", "no stage '" + name + "' in the timed frames (they recorded: " + known + ")");
    }
    return it->second.median;
  }
  // The sum of stage() over `names`.
  double sumOf(const std::vector<std::string>& names) const {
    double sum = 0.0;
    for (auto& n : names) sum += stage(n);
    return sum;
  }
};

// A Technique::statistics() value of a frame, if the technique reports it.
inline std::optional<double> findStatistic(const FrameResult& f, const std::string& key) {
  for (auto& [k, v] : f.statistics)
    if (k == key) return v;
  return std::nullopt;
}
// ... 0 if the technique does not report it.
inline double frameStatistic(const FrameResult& f, const std::string& key) {
  return findStatistic(f, key).value_or(0.0);
}

// Calls render(0) `warmup` times, then render(i) for i = 0..frames-1 (at least one), and
// gives each timed frame to onFrame(i, frame) before it is kept as Timing::last. Stage spreads
// are over the timed frames; "prepare" (a technique's once-per-scene work) is left out of them
// and reported as the longest seen (renders of a moving scene prepare every frame).
template <class Render, class OnFrame>
Timing timeRenders(int frames, int warmup, Render&& render, OnFrame&& onFrame) {
  std::map<std::string, std::vector<double>> stages, harnessStages;
  std::vector<double> total, harness;
  Timing t;
  frames = std::max(frames, 1);
  for (int f = 0; f < warmup + frames; ++f) {
    const int i = std::max(0, f - warmup);
    t.last = render(i);
    for (auto& st : t.last.timer.stages())
      if (st.stage == "prepare") t.prepareMs = std::max(t.prepareMs, st.ms);
    if (f < warmup) continue;
    double sum = 0, harnessSum = 0;
    for (auto& st : t.last.timer.stages()) {
      if (st.stage == "prepare") continue;
      const bool h = st.kind == StageKind::Harness;
      (h ? harnessStages : stages)[st.stage].push_back(st.ms);
      (h ? harnessSum : sum) += st.ms;
    }
    total.push_back(sum);
    harness.push_back(harnessSum);
    onFrame(i, t.last);
  }
  for (auto& [name, v] : stages) t.stages[name] = spread(v);
  for (auto& [name, v] : harnessStages) t.harnessStages[name] = spread(v);
  t.total = spread(total);
  t.harness = spread(harness);
  return t;
}

// The same frame `frames` times on one renderer, after `warmup` untimed ones.
inline Timing timeFrames(Renderer& renderer, Technique& technique, int frames, int warmup) {
  return timeRenders(
      frames, warmup, [&](int) { return renderer.render(technique); }, [](int, const FrameResult&) {});
}

}  // namespace penumbra
