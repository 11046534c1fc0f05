// ParamSpec declarations and TechniqueParams (pipeline/technique.h): the checked `--param
// key=value` set techniques read, through their own declarations (TechniqueArgs).
#include "pipeline/technique.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "core/key_values.h"

namespace penumbra {

// ---- ParamSpec -------------------------------------------------------------------------------

ParamSpec ParamSpec::integer(std::string key, int fallback, int lo, int hi, std::string meaning) {
  ParamSpec p;
  p.key = std::move(key), p.type = Type::Integer, p.fallback = fallback, p.lo = lo, p.hi = hi,
  p.meaning = std::move(meaning);
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
ParamSpec ParamSpec::choice(std::string key, std::string fallback, std::vector<std::string> choices,
                            std::string meaning) {
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
    case Type::Integer:
    case Type::Number:
      return fmt::format("{}", fallback);
    case Type::Boolean:
      return fallback != 0.0 ? "1" : "0";
    case Type::Choice:
      return text;
    case Type::Text:
      return text.empty() ? "(none)" : text;
  }
  return {};
}
std::string ParamSpec::rangeText() const {
  switch (type) {
    case Type::Integer:
    case Type::Number:
      return fmt::format("[{}, {}]", lo, hi);
    case Type::Boolean:
      return "0/1";
    case Type::Choice: {
      std::string out;
      for (auto& c : choices) out += (out.empty() ? "" : "|") + c;
      return out;
    }
    case Type::Text:
      return "path";
  }
  return {};
}

const char* toString(TechniqueFamily f) {
  switch (f) {
    case TechniqueFamily::ExactPerSample:
      return "exact per sample";
    case TechniqueFamily::MultiView:
      return "multi-view maps";
    case TechniqueFamily::SingleMap:
      return "single map";
    case TechniqueFamily::Denoised:
      return "denoised rays";
    case TechniqueFamily::Hard:
      return "hard / unshadowed";
  }
  return "?";
}

const ParamSpec& TechniqueArgs::spec(const std::string& key) const {
  for (auto& p : declared_)
    if (p.key == key) return p;
  checkFailed(("technique '" + technique_ + "' reads '" + key + "' it does not declare").c_str(), __FILE__, __LINE__,
              "declare every parameter in the technique's ParamSpec list");
}

// ---- TechniqueParams -------------------------------------------------------------------------

TechniqueParams::TechniqueParams(const std::vector<std::string>& keyValues, std::vector<std::string> swept)
    : swept_(std::move(swept)) {
  for (auto& kv : keyValues) {
    auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == kv.size())
      throw Error("param", "expected key=value, got '" + kv + "'", ExitCode::Usage);
    std::string key = kv.substr(0, eq);
    // A plain lookup, not find(): find() records the key as one a technique knows, which made
    // an unread key list itself as known ("(known: bogus)").
    for (auto& [k, v] : values_)
      if (k == key) throw Error("param", "key '" + key + "' given twice", ExitCode::Usage);
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

std::string TechniqueParams::origin(const std::string& key) const {
  return std::find(swept_.begin(), swept_.end(), key) != swept_.end() ? "sweep" : "param";
}

KeyPlace TechniqueParams::place(const ParamSpec& spec) const { return {origin(spec.key), spec.key, ExitCode::Usage}; }

int TechniqueParams::integer(const ParamSpec& spec) const {
  PENUMBRA_CHECK(spec.type == ParamSpec::Type::Integer, "integer read of a non-integer parameter");
  const std::string* v = find(spec.key);
  return v ? readInteger(KeyValue::ofText(*v), place(spec), int(spec.lo), int(spec.hi)) : int(spec.fallback);
}

double TechniqueParams::number(const ParamSpec& spec) const {
  PENUMBRA_CHECK(spec.type == ParamSpec::Type::Number, "number read of a non-number parameter");
  const std::string* v = find(spec.key);
  return v ? readNumber(KeyValue::ofText(*v), place(spec), spec.lo, spec.hi) : spec.fallback;
}

bool TechniqueParams::boolean(const ParamSpec& spec) const {
  PENUMBRA_CHECK(spec.type == ParamSpec::Type::Boolean, "boolean read of a non-boolean parameter");
  const std::string* v = find(spec.key);
  return v ? readBoolean(KeyValue::ofText(*v), place(spec)) : spec.fallback != 0.0;
}

std::string TechniqueParams::text(const ParamSpec& spec) const {
  PENUMBRA_CHECK(spec.type == ParamSpec::Type::Choice || spec.type == ParamSpec::Type::Text,
                 "text read of a value parameter");
  const std::string* v = find(spec.key);
  if (!v) return spec.text;
  if (spec.type == ParamSpec::Type::Text) return readString(KeyValue::ofText(*v), place(spec));
  return spec.choices[std::size_t(readChoice(KeyValue::ofText(*v), place(spec), spec.choices))];
}

void TechniqueParams::checkConsumed() const {
  for (auto& [k, v] : values_)
    if (std::find(consumed_.begin(), consumed_.end(), k) == consumed_.end()) {
      std::string known;
      for (auto& n : known_) known += (known.empty() ? "" : ", ") + n;
      throw Error(origin(k),
                  "no technique of this run has a parameter '" + k + "' (" +
                      (known.empty() ? "they take no parameters" : "known: " + known) + ")",
                  ExitCode::Usage);
    }
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
