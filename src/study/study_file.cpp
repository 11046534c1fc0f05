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
#include "pipeline/renderer.h"
#include "sampling/light_samples.h"
#include "scene/variants.h"
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
  // A "key": value object as "key=value" strings, in key order.
  const auto pairs = [](Object& o, const std::string& key) {
    std::vector<std::string> out;
    const json& p = o.raw(key);
    if (!p.is_object()) o.place(key).fail("must be an object of key: value");
    for (auto it = p.begin(); it != p.end(); ++it)
      out.push_back(it.key() + "=" + (it.value().is_string() ? it.value().get<std::string>() : it.value().dump()));
    return out;
  };
  if (j.is_string()) {
    t.name = j.get<std::string>();
    t.paramSets = {{}};
  } else {
    Object o(j, place.where, place.at);
    if (!o.has("name")) place.fail("name: missing");
    t.name = readString(valueOf(o.raw("name")), o.place("name"));
    const std::vector<std::string> fixed = o.has("params") ? pairs(o, "params") : std::vector<std::string>{};
    t.paramSets = o.has("sweep") ? expandSweeps(o.raw("sweep"), place.where, o.place("sweep").at)
                                 : std::vector<std::vector<std::string>>{{}};
    for (auto& set : t.paramSets) set.insert(set.begin(), fixed.begin(), fixed.end());
    if (o.has("profile")) {
      t.profile = pairs(o, "profile");
      if (t.profile.empty()) o.place("profile").fail("must not be empty");
    }
    o.refuseUnknown();
  }
  // Every parameter set (and with the profiled frame's parameters) is checked by making the
  // technique (no GL: a technique's constructor reads its parameters only); its errors are the
  // study's.
  try {
    const TechniqueInfo& info = findTechnique(t.name);
    for (const auto& set : t.paramSets)
      for (bool profiled : {false, true}) {
        if (profiled && t.profile.empty()) continue;
        std::vector<std::string> all = set;
        if (profiled) all.insert(all.end(), t.profile.begin(), t.profile.end());
        const TechniqueParams params(all);
        info.make(params);
        params.checkConsumed();
      }
  } catch (const Error& e) {
    place.fail(e.what());
  }
  return t;
}

// A scene entry: a file or glob (or "default"), or {"file": ..., variant keys...}.
std::vector<SceneEntry> readScenes(const json& j, const fs::path& base, const KeyPlace& place) {
  if (j.is_string()) {
    std::vector<SceneEntry> out;
    for (auto& path : expandScene(j.get<std::string>(), base, place)) out.push_back({path, {}});
    return out;
  }
  Object o(j, place.where, place.at);
  if (!o.has("file")) place.fail("file: missing");
  const std::string file = readString(valueOf(o.raw("file")), o.place("file"));
  std::vector<std::string> variant;
  for (const std::string& key : sceneVariantKeys())
    if (o.has(key)) {
      const json& v = o.raw(key);
      if (!v.is_number()) o.place(key).fail("must be a number, got " + abbreviate(v.dump()));
      variant.push_back(key + "=" + v.dump());
    }
  o.refuseUnknown();
  checkSceneVariant(variant, place);
  std::vector<SceneEntry> out;
  for (auto& path : expandScene(file, base, o.place("file"))) out.push_back({path, variant});
  return out;
}

// The axes of the study's top level, or of one of its parts (`defaults`: the top level's).
StudyAxes readAxes(Object& o, const StudyAxes& defaults, const fs::path& base) {
  StudyAxes a = defaults;
  if (o.has("scenes")) {
    a.scenes.clear();
    for (auto& group : o.list("scenes", [&](const json&v, const KeyPlace&p) { return readScenes(v, base, p); }))
      for (auto& scene : group)
        if (std::find(a.scenes.begin(), a.scenes.end(), scene) == a.scenes.end()) a.scenes.push_back(scene);
  }
  if (o.has("techniques")) a.techniques = o.list("techniques", readTechnique);
  if (o.has("samples"))
    a.samples = o.list("samples", [](const json& v, const KeyPlace& p) {
      return readInteger(valueOf(v), p, 1, PENUMBRA_MAX_SAMPLES);
    });
  if (o.has("sizes"))
    a.sizes = o.list("sizes", [](const json& v, const KeyPlace& p) {
      if (v.is_array()) {
        if (v.size() != 2) p.fail("a size is a width or [width, height]");
        return Size{readInteger(valueOf(v[0]), p, 1, 16384), readInteger(valueOf(v[1]), p, 1, 16384)};
      }
      return Size{readInteger(valueOf(v), p, 1, 16384), 0};
    });
  if (o.has("seeds"))
    a.seeds = o.list("seeds", [](const json& v, const KeyPlace& p) {
      return std::uint32_t(readInteger(valueOf(v), p, 0, 2147483647));
    });
  // A name among `names` (a kSampleStrategyNames-like table).
  const auto named = [](const auto& names, const char* what) {
    return [&names, what](const json& v, const KeyPlace& p) {
      const std::string name = readString(valueOf(v), p);
      if (!valueNamed(names, name)) p.fail(fmt::format("unknown {} '{}' ({})", what, name, namesOf(names)));
      return name;
    };
  };
  if (o.has("strategies")) a.strategies = o.list("strategies", named(kSampleStrategyNames, "strategy"));
  if (o.has("shadings")) a.shadings = o.list("shadings", named(kShadingModeNames, "shading mode"));
  if (o.has("patterns")) a.patterns = o.list("patterns", named(kPixelPatternNames, "pixel pattern"));
  if (o.has("light-scales"))
    a.lightScales = o.list("light-scales", [](const json& v, const KeyPlace& p) {
      const double x = readNumber(valueOf(v), p, 0.0, 1e6);
      if (!(x > 0.0)) p.fail("must be greater than 0");
      return x;
    });
  a.frames = o.integer("frames", a.frames, 1, 100);
  a.warmup = o.integer("warmup", a.warmup, 0, 100);
  if (o.has("reference")) {
    Object r(o.raw("reference"), o.place("reference").where, o.place("reference").at);
    if (r.has("converged")) a.converged = readBoolean(valueOf(r.raw("converged")), r.place("converged"));
    a.convergedSamples = r.integer("converged-samples", a.convergedSamples, 16, 1 << 20);
    r.refuseUnknown();
  }
  return a;
}

}  // namespace

std::vector<StudyAxes> StudySpec::products() const {
  return parts.empty() ? std::vector<StudyAxes>{static_cast<const StudyAxes&>(*this)} : parts;
}

std::vector<SceneEntry> StudySpec::allScenes() const {
  std::vector<SceneEntry> out;
  for (const StudyAxes& p : products())
    for (const SceneEntry& e : p.scenes)
      if (std::find(out.begin(), out.end(), e) == out.end()) out.push_back(e);
  return out;
}

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
  static_cast<StudyAxes&>(s) = readAxes(o, StudyAxes{}, base);
  if (o.has("parts")) {
    std::size_t i = 0;
    for (const json& part : o.list("parts", [](const json&v, const KeyPlace&) { return v; })) {
      Object p(part, path, fmt::format("parts[{}]", i++));
      s.parts.push_back(readAxes(p, s, base));
      p.refuseUnknown();
    }
  }
  // Every product needs scenes and techniques, from its part or the top level.
  const std::vector<StudyAxes> products = s.products();
  for (std::size_t i = 0; i < products.size(); ++i)
    for (const auto& [key, empty] :
         {std::pair{"scenes", products[i].scenes.empty()}, std::pair{"techniques", products[i].techniques.empty()}})
      if (empty) (s.parts.empty() ? o.place(key) : o.place(fmt::format("parts[{}].{}", i, key))).fail("missing");
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
  std::uint64_t total = 0;
  for (const StudyAxes& a : s.products()) {
    std::uint64_t sets = 0;
    for (const TechniqueAxis& t : a.techniques) sets += t.paramSets.size();
    const std::uint64_t configurations = std::uint64_t(a.scenes.size()) * a.samples.size() * a.sizes.size() *
                                         a.seeds.size() * a.strategies.size() * a.lightScales.size() *
                                         a.shadings.size() * a.patterns.size();
    const std::uint64_t converged =
        a.converged ? std::uint64_t(a.scenes.size()) * a.sizes.size() * a.lightScales.size() : 0;
    total += configurations * (sets + 1) + converged;
  }
  return total;
}

}  // namespace penumbra::study
