#include "study/study_file.h"

#include <glob.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/key_values.h"
#include "core/names.h"
#include "sampling/light_samples.h"
#include "techniques/registry.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace penumbra::study {
namespace {

constexpr std::uint64_t kMostJobs = 1'000'000;

KeyValue valueOf(const json& j) {
  KeyValue v;
  v.shown = j.dump();
  if (j.is_number_integer() || j.is_number_unsigned())
    v.kind = KeyValue::Kind::Integer, v.number = j.get<double>();
  else if (j.is_number())
    v.kind = KeyValue::Kind::Number, v.number = j.get<double>();
  else if (j.is_boolean())
    v.kind = KeyValue::Kind::Boolean, v.boolean = j.get<bool>();
  else if (j.is_string())
    v.kind = KeyValue::Kind::String, v.text = j.get<std::string>();
  return v;
}

// The reader of one JSON object: typed, range-checked values; unknown keys refused at the end.
class Object {
 public:
  Object(const json& j, std::string file, std::string at) : j_(j), file_(std::move(file)), at_(std::move(at)) {
    if (!j_.is_object()) place("").fail("must be an object, got " + abbreviate(j_.dump()));
  }
  KeyPlace place(const std::string& key) const {
    const std::string where = at_.empty() ? key : key.empty() ? at_ : at_ + "." + key;
    return {file_, where.empty() ? "(top level)" : where, ExitCode::Usage};
  }
  bool has(const std::string& key) {
    known_.insert(key);
    return j_.contains(key);
  }
  const json& raw(const std::string& key) {
    known_.insert(key);
    return j_.at(key);
  }
  // A non-empty array of `read` items, or one item standing for itself.
  template <class Read>
  auto list(const std::string& key, Read read) {
    using T = decltype(read(json(), KeyPlace()));
    std::vector<T> out;
    const json& v = raw(key);
    if (!v.is_array()) return std::vector<T>{read(v, place(key))};
    if (v.empty()) place(key).fail("must not be empty");
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(read(v[i], place(fmt::format("{}[{}]", key, i))));
    return out;
  }
  int integer(const std::string& key, int fallback, int lo, int hi) {
    return has(key) ? readInteger(valueOf(raw(key)), place(key), lo, hi) : fallback;
  }
  void refuseUnknown() const {
    std::vector<std::string> known(known_.begin(), known_.end());
    for (auto it = j_.begin(); it != j_.end(); ++it)
      if (!known_.count(it.key())) place(it.key()).fail("unknown key (known: " + joinKeys(known) + ")");
  }

 private:
  const json& j_;
  std::string file_, at_;
  std::set<std::string> known_;
};

// Scenes: "default", files, or globs (sorted), relative to the study's folder; absolute
// canonical paths, so that a job runs from any working directory.
std::vector<std::string> expandScene(const std::string& pattern, const fs::path& base, const KeyPlace& place) {
  if (pattern == "default") return {pattern};
  const std::string full = fs::path(pattern).is_absolute() ? pattern : (base / pattern).string();
  glob_t g{};
  const int rc = ::glob(full.c_str(), GLOB_NOSORT, nullptr, &g);
  std::vector<std::string> out;
  if (rc == 0)
    for (std::size_t i = 0; i < g.gl_pathc; ++i) out.push_back(fs::weakly_canonical(g.gl_pathv[i]).string());
  globfree(&g);
  if (out.empty())
    place.fail(full.find_first_of("*?[") == std::string::npos ? "no such file: " + full : "matches no file: " + full);
  std::sort(out.begin(), out.end());
  return out;
}

// The product of a technique's sweeps: {"key": [v1, v2], ...} -> every combination, keys in order.
std::vector<std::vector<std::string>> expandSweeps(const json& sweeps, const std::string& file, const std::string& at) {
  std::vector<std::vector<std::string>> sets{{}};
  if (!sweeps.is_object()) KeyPlace{file, at, ExitCode::Usage}.fail("must be an object of key: [values]");
  for (auto it = sweeps.begin(); it != sweeps.end(); ++it) {
    const KeyPlace place{file, at + "." + it.key(), ExitCode::Usage};
    const json values = it.value().is_array() ? it.value() : json::array({it.value()});
    if (values.empty()) place.fail("must not be empty");
    std::vector<std::vector<std::string>> next;
    for (const auto& set : sets)
      for (const json& v : values) {
        if (!(v.is_number() || v.is_boolean() || v.is_string()))
          place.fail("values must be numbers, booleans or strings");
        auto s = set;
        s.push_back(it.key() + "=" + (v.is_string() ? v.get<std::string>() : v.dump()));
        next.push_back(std::move(s));
      }
    sets = std::move(next);
  }
  return sets;
}

TechniqueAxis readTechnique(const json& j, const KeyPlace& place) {
  TechniqueAxis t;
  if (j.is_string()) {
    t.name = j.get<std::string>();
    t.paramSets = {{}};
  } else {
    Object o(j, place.where, place.at);
    if (!o.has("name")) place.fail("name: missing");
    t.name = readString(valueOf(o.raw("name")), o.place("name"));
    std::vector<std::string> fixed;
    if (o.has("params")) {
      const json& p = o.raw("params");
      if (!p.is_object()) o.place("params").fail("must be an object of key: value");
      for (auto it = p.begin(); it != p.end(); ++it)
        fixed.push_back(it.key() + "=" + (it.value().is_string() ? it.value().get<std::string>() : it.value().dump()));
    }
    t.paramSets = o.has("sweep") ? expandSweeps(o.raw("sweep"), place.where, o.place("sweep").at)
                                 : std::vector<std::vector<std::string>>{{}};
    for (auto& set : t.paramSets) set.insert(set.begin(), fixed.begin(), fixed.end());
    o.refuseUnknown();
  }
  // Every parameter set is checked by making the technique (no GL: a technique's constructor
  // reads its parameters only); its errors are the study's.
  try {
    const TechniqueInfo& info = findTechnique(t.name);
    for (const auto& set : t.paramSets) {
      const TechniqueParams params(set);
      info.make(params);
      params.checkConsumed();
    }
  } catch (const Error& e) {
    place.fail(e.what());
  }
  return t;
}

}  // namespace

StudySpec readStudy(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open the study file", ExitCode::Usage);
  json j;
  try {
    j = json::parse(in);
  } catch (const json::exception& e) {
    throw Error(path, std::string("not valid JSON: ") + e.what(), ExitCode::Usage);
  }
  StudySpec s;
  s.path = path;
  Object o(j, path, "");
  const fs::path base = fs::path(path).parent_path();
  s.name = o.has("name") ? readString(valueOf(o.raw("name")), o.place("name")) : fs::path(path).stem().string();
  for (const char* required : {"scenes", "techniques"})
    if (!o.has(required)) o.place(required).fail("missing");
  for (auto& group : o.list(
           "scenes", [&](const json&v, const KeyPlace&p) { return expandScene(readString(valueOf(v), p), base, p); }))
    for (auto& scene : group)
      if (std::find(s.scenes.begin(), s.scenes.end(), scene) == s.scenes.end()) s.scenes.push_back(scene);
  s.techniques = o.list("techniques", readTechnique);
  s.samples =
      o.has("samples")
          ? o.list("samples",
                   [](const json& v, const KeyPlace& p) { return readInteger(valueOf(v), p, 1, PENUMBRA_MAX_SAMPLES); })
          : std::vector<int>{16};
  s.sizes =
      o.has("sizes")
          ? o.list("sizes",
                   [](const json& v, const KeyPlace& p) {
                     if (v.is_array()) {
                       if (v.size() != 2) p.fail("a size is a width or [width, height]");
                       return Size{readInteger(valueOf(v[0]), p, 1, 16384), readInteger(valueOf(v[1]), p, 1, 16384)};
                     }
                     return Size{readInteger(valueOf(v), p, 1, 16384), 0};
                   })
          : std::vector<Size>{{128, 0}};
  s.seeds = o.has("seeds") ? o.list("seeds",
                                    [](const json& v, const KeyPlace& p) {
                                      return std::uint32_t(readInteger(valueOf(v), p, 0, 2147483647));
                                    })
                           : std::vector<std::uint32_t>{1};
  s.strategies = o.has("strategies")
                     ? o.list("strategies",
                              [](const json& v, const KeyPlace& p) {
                                const std::string name = readString(valueOf(v), p);
                                if (!valueNamed(kSampleStrategyNames, name))
                                  p.fail("unknown strategy '" + name + "' (" + namesOf(kSampleStrategyNames) + ")");
                                return name;
                              })
                     : std::vector<std::string>{"stratified"};
  if (o.has("reference")) {
    Object r(o.raw("reference"), path, "reference");
    if (r.has("converged")) s.converged = readBoolean(valueOf(r.raw("converged")), r.place("converged"));
    s.convergedSamples = r.integer("converged-samples", s.convergedSamples, 16, 1 << 20);
    r.refuseUnknown();
  }
  s.frames = o.integer("frames", s.frames, 1, 100);
  s.warmup = o.integer("warmup", s.warmup, 0, 100);
  if (o.has("images")) {
    s.images = readString(valueOf(o.raw("images")), o.place("images"));
    if (s.images != "all" && s.images != "png" && s.images != "none")
      o.place("images").fail("'" + abbreviate(s.images) + "' is not all, png or none");
  }
  o.refuseUnknown();
  const std::uint64_t jobs = jobCount(s);
  if (jobs > kMostJobs)
    throw Error(path, fmt::format("the study expands to {} jobs, more than {} (narrow an axis)", jobs, kMostJobs),
                ExitCode::Usage);
  return s;
}

std::uint64_t jobCount(const StudySpec& s) {
  std::uint64_t sets = 0;
  for (const TechniqueAxis& t : s.techniques) sets += t.paramSets.size();
  const std::uint64_t configurations =
      std::uint64_t(s.scenes.size()) * s.samples.size() * s.sizes.size() * s.seeds.size() * s.strategies.size();
  const std::uint64_t converged = s.converged ? std::uint64_t(s.scenes.size()) * s.sizes.size() : 0;
  return configurations * (sets + 1) + converged;
}

}  // namespace penumbra::study
