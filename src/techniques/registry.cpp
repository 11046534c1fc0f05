// The explicit table of techniques: name -> factory. Add a technique here and nowhere else.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "core/key_values.h"
#include "pipeline/technique.h"
#include "techniques/dcs/dcs.h"
#include "techniques/hard_sv/hard_sv.h"
#include "techniques/mvr/mvr.h"
#include "techniques/none/none.h"
#include "techniques/pcss/pcss.h"
#include "techniques/raytrace/raytrace.h"
#include "techniques/reproject/reproject.h"
#include "techniques/vssm/vssm.h"
#include "techniques/vwss/vwss.h"

namespace penumbra {

namespace {
DcsOptions dcsPreset(SilhouetteMode silhouettes, dcs::OpacityMode opacity, int coverage) {
  DcsOptions o;
  o.silhouettes = silhouettes;
  o.opacity = opacity;
  o.coverage = coverage;
  return o;
}
TechniqueInfo dcsEntry(std::string name, std::string description, DcsOptions preset) {
  return {std::move(name), std::move(description), dcsParams(preset),
          [](const TechniqueArgs& a) { return makeDepthComplexitySampling(readDcsOptions(a)); }};
}
// A technique that is a preset of a family: the family's declarations with the preset's
// defaults, and its factory.
template <class Preset>
TechniqueInfo presetEntry(std::string name, std::string description, std::vector<ParamSpec> params, Preset preset,
                          std::unique_ptr<Technique> (*make)(const TechniqueArgs&, Preset)) {
  return {std::move(name), std::move(description), std::move(params),
          [preset, make](const TechniqueArgs& a) { return make(a, preset); }};
}
TechniqueInfo pcssEntry(std::string name, std::string description, PcssOptions preset) {
  return presetEntry(std::move(name), std::move(description), pcssParams(preset), preset, makePercentageCloserSoftShadows);
}
TechniqueInfo vssmEntry(std::string name, std::string description, VssmOptions preset) {
  return presetEntry(std::move(name), std::move(description), vssmParams(preset), preset, makeVarianceSoftShadowMapping);
}
TechniqueInfo vwssEntry(std::string name, std::string description, VwssMode mode) {
  return presetEntry(std::move(name), std::move(description), vwssParams(mode), mode, makeViewWarpedSoftShadows);
}
VssmOptions vssmPreset(bool exactSat, int shadowLevels) {
  VssmOptions o;
  o.exactSat = exactSat;
  o.shadowLevels = shadowLevels;
  return o;
}
}  // namespace

const std::vector<TechniqueInfo>& techniqueTable() {
  using dcs::OpacityMode;
  static const std::vector<TechniqueInfo> table = {
      {"none", "unshadowed direct lighting", {}, [](const TechniqueArgs&) { return makeUnshadowed(); }},
      {"hard-sv", "hard shadows from the light centre, z-fail shadow volumes (float counter)", {},
       [](const TechniqueArgs&) { return makeHardShadowVolumes(); }},
      dcsEntry("dcs", "depth complexity sampling: per-sample occluder counts, accurate silhouettes (exact; semi-opaque layers multiply)",
               dcsPreset(SilhouetteMode::Accurate, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_EXACT)),
      dcsEntry("dcs-standard", "depth complexity sampling with standard silhouettes (from the light centre)",
               dcsPreset(SilhouetteMode::Standard, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_EXACT)),
      dcsEntry("dcs-sum", "depth complexity sampling, semi-opaque occluders as the paper's sum of opacities",
               dcsPreset(SilhouetteMode::Accurate, OpacityMode::Sum, PENUMBRA_DCS_COVERAGE_EXACT)),
      dcsEntry("dcs-naive", "dcs with the paper's covered-sample loop over 8-bit packed positions (approximate)",
               dcsPreset(SilhouetteMode::Accurate, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_NAIVE)),
      dcsEntry("dcs-lut", "dcs with the paper's edge LUT (cube-map sectors & line table, approximate)",
               dcsPreset(SilhouetteMode::Accurate, OpacityMode::Product, PENUMBRA_DCS_COVERAGE_LUT)),
      {"mvr", "multi-view rasterisation: a depth map per light sample, one draw each, PCF (VWSS paper's reference)",
       mvrParams(), [](const TechniqueArgs& a) { return makeMultiViewRasterisation(a, false); }},
      {"mvr-layered", "mvr in one instanced draw, a geometry shader routing instances to map layers", mvrParams(),
       [](const TechniqueArgs& a) { return makeMultiViewRasterisation(a, true); }},
      vwssEntry("vwss", "view-warped soft shadows: points from one enlarged central view, compute splat (buffered)",
                VwssMode::Buffered),
      vwssEntry("vwss-unbuffered", "vwss splatting from the point-generation fragment shader (no point buffer)",
                VwssMode::Unbuffered),
      vwssEntry("vwss-graphics", "vwss's points drawn as GL_POINTS, a draw per map, depth-tested (graphics pipeline)",
                VwssMode::Graphics),
      {"reproject", "fragment reprojection: the central z-buffered map reprojected into every map (atomics)",
       reprojectParams(), [](const TechniqueArgs& a) { return makeFragmentReprojection(a, true); }},
      {"reproject-unsync", "fragment reprojection without synchronisation (last writer wins)", reprojectParams(),
       [](const TechniqueArgs& a) { return makeFragmentReprojection(a, false); }},
      pcssEntry("pcss", "percentage-closer soft shadows, one map from the light centre, Vogel disk + noise (Sterna: 32 blocker, 16 PCF samples)",
                pcssPreset(PcssMode::Regular, false, false)),
      pcssEntry("pcss-ultra", "pcss with the 'Ultra' preset the VWSS paper compares with (64 blocker, 96 PCF samples)",
                pcssPreset(PcssMode::Regular, true, false)),
      pcssEntry("pcss-mask", "pcss with Sterna's quarter-resolution blurred penumbra mask (kernel scale 1.4)",
                pcssPreset(PcssMode::PenumbraMask, false, false)),
      pcssEntry("pcss-minfilter", "pcss with Sterna's min filter: blocker depth from the separable nearest-depth filter of the map, blurred",
                pcssPreset(PcssMode::MinFilter, false, false)),
      pcssEntry("pcss-dense", "pcss as Fernando's original: every texel of the blocker-search and filter kernels (at most 32x32)",
                pcssPreset(PcssMode::Dense, false, false)),
      pcssEntry("pcss-checker", "pcss computed on a checkerboard (half the pixels), depth-aware upsampling",
                pcssPreset(PcssMode::Regular, false, true)),
      vssmEntry("vssm", "variance soft shadow mapping: exact summed-area table of depth moments, min-max HSM, 5x5 uniform blocker / H=3 adaptive shadow subdivision, contact fallback",
                VssmOptions{}),
      vssmEntry("vssm-uniform", "vssm with uniform subdivision for both kernels (5x5 blocker, 8x8 shadow)",
                vssmPreset(true, 0)),
      vssmEntry("vssm-fp32", "vssm on a plain fp32 summed-area table (fails at large maps: hard case 17)",
                vssmPreset(false, VssmOptions{}.shadowLevels)),
      {"raytrace", "Embree reference with the same light samples as every technique (per sample)", {},
       [](const TechniqueArgs&) { return makeRaytraceSameSamples(); }},
      {"raytrace-converged", "Embree reference, 1024 stratified samples per pixel (visibility only)", {},
       [](const TechniqueArgs&) { return makeRaytraceConverged(1024); }},
  };
  return table;
}

const TechniqueInfo& findTechnique(const std::string& name) {
  std::string known;
  for (auto& t : techniqueTable()) {
    if (t.name == name) return t;
    known += (known.empty() ? "" : ", ") + t.name;
  }
  throw Error("--technique", "unknown technique '" + name + "' (known: " + known + ")", ExitCode::Usage);
}

std::unique_ptr<Technique> makeTechnique(const std::string& name, const TechniqueParams& params) {
  const TechniqueInfo& info = findTechnique(name);
  return info.create(TechniqueArgs(params, info.params, info.name));
}

// ---- ParamSpec -------------------------------------------------------------------------------

ParamSpec ParamSpec::integer(std::string key, int fallback, int lo, int hi, std::string meaning) {
  ParamSpec p;
  p.key = std::move(key), p.type = Type::Integer, p.fallback = fallback, p.lo = lo, p.hi = hi, p.meaning = std::move(meaning);
  return p;
}
ParamSpec ParamSpec::number(std::string key, double fallback, double lo, double hi, std::string meaning) {
  ParamSpec p = integer(std::move(key), 0, 0, 0, std::move(meaning));
  p.type = Type::Number, p.fallback = fallback, p.lo = lo, p.hi = hi;
  return p;
}
ParamSpec ParamSpec::boolean(std::string key, bool fallback, std::string meaning) {
  ParamSpec p = integer(std::move(key), fallback ? 1 : 0, 0, 1, std::move(meaning));
  p.type = Type::Boolean;
  return p;
}
ParamSpec ParamSpec::choice(std::string key, std::string fallback, std::vector<std::string> choices, std::string meaning) {
  PENUMBRA_CHECK(std::find(choices.begin(), choices.end(), fallback) != choices.end(), "choice default not a choice");
  ParamSpec p = integer(std::move(key), 0, 0, 0, std::move(meaning));
  p.type = Type::Choice, p.text = std::move(fallback), p.choices = std::move(choices);
  return p;
}
ParamSpec ParamSpec::path(std::string key, std::string meaning) {
  ParamSpec p = integer(std::move(key), 0, 0, 0, std::move(meaning));
  p.type = Type::Text;
  return p;
}
ParamSpec ParamSpec::withDefault(double value) const {
  ParamSpec p = *this;
  p.fallback = value;
  return p;
}
ParamSpec ParamSpec::withDefault(std::string value) const {
  ParamSpec p = *this;
  p.text = std::move(value);
  return p;
}
ParamSpec ParamSpec::shown(std::string rule) const {
  ParamSpec p = *this;
  p.shownDefault = std::move(rule);
  return p;
}
std::string ParamSpec::defaultText() const {
  if (!shownDefault.empty()) return shownDefault;
  switch (type) {
    case Type::Integer: case Type::Number: return fmt::format("{}", fallback);
    case Type::Boolean: return fallback != 0.0 ? "1" : "0";
    case Type::Choice: return text;
    case Type::Text: return text.empty() ? "(none)" : text;
  }
  return {};
}
std::string ParamSpec::rangeText() const {
  switch (type) {
    case Type::Integer: case Type::Number: return fmt::format("[{}, {}]", lo, hi);
    case Type::Boolean: return "0/1";
    case Type::Choice: {
      std::string out;
      for (auto& c : choices) out += (out.empty() ? "" : "|") + c;
      return out;
    }
    case Type::Text: return "path";
  }
  return {};
}

const ParamSpec& TechniqueArgs::spec(const std::string& key) const {
  for (auto& p : declared_)
    if (p.key == key) return p;
  checkFailed(("technique '" + technique_ + "' reads '" + key + "' it does not declare").c_str(), __FILE__, __LINE__,
              "declare every parameter in the technique's ParamSpec list");
}

// ---- TechniqueParams -------------------------------------------------------------------------

TechniqueParams::TechniqueParams(const std::vector<std::string>& keyValues) {
  for (auto& kv : keyValues) {
    auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == kv.size())
      throw Error("--param", "expected key=value, got '" + kv + "'", ExitCode::Usage);
    std::string key = kv.substr(0, eq);
    // A plain lookup, not find(): find() records the key as one a technique knows, which made
    // an unread key list itself as known ("(known: bogus)").
    for (auto& [k, v] : values_)
      if (k == key) throw Error("--param", "key '" + key + "' given twice", ExitCode::Usage);
    values_.emplace_back(key, kv.substr(eq + 1));
  }
}

const std::string* TechniqueParams::find(const std::string& key) const {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.push_back(key);
  for (auto& [k, v] : values_)
    if (k == key) {
      if (std::find(consumed_.begin(), consumed_.end(), key) == consumed_.end()) consumed_.push_back(key);
      return &v;
    }
  return nullptr;
}

namespace {
KeyPlace paramPlace(const ParamSpec& spec) { return {"--param", spec.key, ExitCode::Usage}; }
}  // namespace

int TechniqueParams::integer(const ParamSpec& spec) const {
  PENUMBRA_CHECK(spec.type == ParamSpec::Type::Integer, "integer read of a non-integer parameter");
  const std::string* v = find(spec.key);
  return v ? readInteger(KeyValue::ofText(*v), paramPlace(spec), int(spec.lo), int(spec.hi)) : int(spec.fallback);
}

double TechniqueParams::number(const ParamSpec& spec) const {
  PENUMBRA_CHECK(spec.type == ParamSpec::Type::Number, "number read of a non-number parameter");
  const std::string* v = find(spec.key);
  return v ? readNumber(KeyValue::ofText(*v), paramPlace(spec), spec.lo, spec.hi) : spec.fallback;
}

bool TechniqueParams::boolean(const ParamSpec& spec) const {
  PENUMBRA_CHECK(spec.type == ParamSpec::Type::Boolean, "boolean read of a non-boolean parameter");
  const std::string* v = find(spec.key);
  return v ? readBoolean(KeyValue::ofText(*v), paramPlace(spec)) : spec.fallback != 0.0;
}

std::string TechniqueParams::text(const ParamSpec& spec) const {
  PENUMBRA_CHECK(spec.type == ParamSpec::Type::Choice || spec.type == ParamSpec::Type::Text, "text read of a value parameter");
  const std::string* v = find(spec.key);
  if (!v) return spec.text;
  if (spec.type == ParamSpec::Type::Text) return readString(KeyValue::ofText(*v), paramPlace(spec));
  return spec.choices[std::size_t(readChoice(KeyValue::ofText(*v), paramPlace(spec), spec.choices))];
}

void TechniqueParams::checkConsumed() const {
  for (auto& [k, v] : values_)
    if (std::find(consumed_.begin(), consumed_.end(), k) == consumed_.end()) {
      std::string known;
      for (auto& n : known_) known += (known.empty() ? "" : ", ") + n;
      throw Error("--param", "no technique of this run has a parameter '" + k + "' (" +
                                 (known.empty() ? "they take no parameters" : "known: " + known) + ")",
                  ExitCode::Usage);
    }
}

std::vector<std::string> TechniqueParams::given() const {
  std::vector<std::string> out;
  for (auto& [k, v] : values_) out.push_back(k + "=" + v);
  return out;
}

std::vector<std::string> TechniqueParams::read() const {
  std::vector<std::string> out;
  for (auto& [k, v] : values_)
    if (std::find(consumed_.begin(), consumed_.end(), k) != consumed_.end()) out.push_back(k + "=" + v);
  return out;
}

void TechniqueParams::noteReads(const TechniqueParams& other) {
  auto merge = [](std::vector<std::string>& into, const std::vector<std::string>& from) {
    for (auto& k : from)
      if (std::find(into.begin(), into.end(), k) == into.end()) into.push_back(k);
  };
  merge(known_, other.known_);
  merge(consumed_, other.consumed_);
}

}  // namespace penumbra
