// TechniqueParams (pipeline/technique.h): the checked `--param key=value` set techniques read.
#include "pipeline/technique.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra {

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
double parseNumber(const std::string& key, const std::string& v, double lo, double hi) {
  std::size_t used = 0;
  double x = 0.0;
  try {
    x = std::stod(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || !std::isfinite(x))
    throw Error("--param", key + ": expected a number, got '" + v + "'", ExitCode::Usage);
  if (x < lo || x > hi)
    throw Error("--param", fmt::format("{}: {} is outside [{}, {}]", key, v, lo, hi), ExitCode::Usage);
  return x;
}
}  // namespace

int TechniqueParams::getInt(const std::string& key, int fallback, int lo, int hi) const {
  const std::string* v = find(key);
  if (!v) return fallback;
  double x = parseNumber(key, *v, lo, hi);
  if (x != std::floor(x)) throw Error("--param", key + ": expected an integer, got '" + *v + "'", ExitCode::Usage);
  return int(x);
}

double TechniqueParams::getDouble(const std::string& key, double fallback, double lo, double hi) const {
  const std::string* v = find(key);
  return v ? parseNumber(key, *v, lo, hi) : fallback;
}

bool TechniqueParams::getBool(const std::string& key, bool fallback) const {
  const std::string* v = find(key);
  if (!v) return fallback;
  if (*v == "1" || *v == "true" || *v == "on") return true;
  if (*v == "0" || *v == "false" || *v == "off") return false;
  throw Error("--param", key + ": expected 0/1, got '" + *v + "'", ExitCode::Usage);
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
