// Presets of a comparison: the cartesian product of its sweep axes (samples, resolution,
// technique parameters), each rendered with its own same-sample reference.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "pipeline/renderer.h"

namespace penumbra {

// One sweep axis (cli/options.h parses "key=v1,v2,..."). Keys: `samples`, `resolution` (the
// image width; the height keeps the scene's aspect) or a technique parameter (--param key).
struct SweepAxis {
  std::string key;
  std::vector<std::string> values;  // as given: labels, file names, --param values
  std::vector<int> integers;        // `samples` and `resolution`: the values as numbers
  // An axis of numbers (`samples` or `resolution`).
  static SweepAxis of(const std::string& key, const std::vector<int>& values);
};

struct ComparePreset {
  std::string label;  // "samples=32 map=512"; empty without sweeps
  std::vector<std::pair<std::string, std::string>> values;
  int width = 0, height = 0, samples = 0;
  std::vector<std::string> params;  // key=value: the fixed parameters and this preset's swept ones
  std::vector<std::string> swept;   // the keys of `params` a sweep gave
  std::string fileSuffix() const;   // "" or "__samples-32_map-512"
};

// The presets of `settings` with the fixed technique parameters `params` (key=value) swept
// along `sweeps`, the first axis varying slowest. A key swept twice, or swept and fixed, is
// refused (Error, ExitCode::Usage).
std::vector<ComparePreset> makePresets(const RenderSettings& settings, const std::vector<std::string>& params,
                                       const std::vector<SweepAxis>& sweeps);

// What a technique renders at a preset, given the parameters it read there: presets with the
// same key render the same thing and are measured once.
std::string renderKey(const ComparePreset& p, const std::vector<std::string>& read);

}  // namespace penumbra
