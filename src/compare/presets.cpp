#include "compare/presets.h"

#include "core/files.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra {

SweepAxis SweepAxis::of(const std::string& key, const std::vector<int>& values) {
  SweepAxis axis{key, {}, values};
  for (int v : values) axis.values.push_back(std::to_string(v));
  return axis;
}

std::string ComparePreset::fileSuffix() const {
  if (values.empty()) return "";
  std::string s = "_";
  for (auto& [k, v] : values) {
    s += "_" + k + "-" + fileNameComponent(v, "_");
  }
  return s;
}

std::vector<ComparePreset> makePresets(const RenderSettings& settings, const std::vector<std::string>& params,
                                       const std::vector<SweepAxis>& sweeps) {
  std::vector<ComparePreset> presets(1);
  presets[0].width = settings.width, presets[0].height = settings.height, presets[0].samples = settings.sampling.count;
  presets[0].params = params;
  std::vector<std::string> seen;
  for (auto& axis : sweeps) {
    if (std::find(seen.begin(), seen.end(), axis.key) != seen.end())
      throw Error("compare", "sweep key '" + axis.key + "' is swept twice", ExitCode::Usage);
    seen.push_back(axis.key);
    bool isParam = axis.key != "samples" && axis.key != "resolution";
    if (isParam)
      for (auto& p : params)
        if (p.rfind(axis.key + "=", 0) == 0)
          throw Error("compare", "sweep key '" + axis.key + "' is also a fixed parameter (" + p + ")", ExitCode::Usage);
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
          p.swept.push_back(axis.key);
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

std::string renderKey(const ComparePreset& p, const std::vector<std::string>& read) {
  std::string key = fmt::format("{}x{} n{}", p.width, p.height, p.samples);
  for (auto& r : read) key += " " + r;
  return key;
}

}  // namespace penumbra
