#include "core/key_values.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <fmt/format.h>

namespace penumbra {

KeyValue KeyValue::ofText(const std::string& text) {
  KeyValue v;
  v.kind = Kind::Text;
  v.text = text;
  v.shown = "'" + text + "'";
  return v;
}

void KeyPlace::fail(const std::string& problem) const {
  throw Error(where, at.empty() ? problem : at + ": " + problem, code);
}

// strtod reads a prefix: the whole text must be read. Decimal only: strtod also reads hex
// ("0x10", "0x1p4"), "inf" and "nan", which a user did not mean as numbers.
bool parseNumber(const std::string& text, double& x) {
  if (text.empty() || text.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
  char* end = nullptr;
  x = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

namespace {

double finiteNumber(const KeyValue& v, const KeyPlace& place) {
  double x = v.number;
  const bool isNumber = v.kind == KeyValue::Kind::Number || v.kind == KeyValue::Kind::Integer ||
                        (v.kind == KeyValue::Kind::Text && parseNumber(v.text, x));
  if (!isNumber) place.fail("expected a number, got " + v.shown);
  if (!std::isfinite(x)) place.fail("not a finite number: " + v.shown);
  return x;
}

void checkRange(double x, const KeyValue& v, const KeyPlace& place, double lo, double hi) {
  if (x < lo || x > hi)
    place.fail(fmt::format("{} is outside [{}, {}]", v.kind == KeyValue::Kind::Text ? v.text : v.shown, lo, hi));
}
}  // namespace

double readNumber(const KeyValue& v, const KeyPlace& place, double lo, double hi) {
  const double x = finiteNumber(v, place);
  checkRange(x, v, place, lo, hi);
  return x;
}

int readInteger(const KeyValue& v, const KeyPlace& place, int lo, int hi) {
  const double x = finiteNumber(v, place);
  if (v.kind == KeyValue::Kind::Number || x != std::floor(x)) place.fail("expected an integer, got " + v.shown);
  checkRange(x, v, place, lo, hi);
  return int(x);
}

bool readBoolean(const KeyValue& v, const KeyPlace& place) {
  if (v.kind == KeyValue::Kind::Boolean) return v.boolean;
  if (v.kind == KeyValue::Kind::Text) {
    if (v.text == "1" || v.text == "true" || v.text == "on") return true;
    if (v.text == "0" || v.text == "false" || v.text == "off") return false;
    place.fail("expected true or false (or 1/0, on/off), got " + v.shown);
  }
  place.fail("expected true or false, got " + v.shown);
}

std::string readString(const KeyValue& v, const KeyPlace& place) {
  if (v.kind != KeyValue::Kind::String && v.kind != KeyValue::Kind::Text)
    place.fail("expected a string, got " + v.shown);
  return v.text;
}

int readChoice(const KeyValue& v, const KeyPlace& place, const std::vector<std::string>& choices) {
  std::string s = v.text;
  if (v.kind == KeyValue::Kind::Integer)
    s = fmt::format("{}", v.number);
  else if (v.kind != KeyValue::Kind::String && v.kind != KeyValue::Kind::Text)
    s.clear();
  for (std::size_t i = 0; i < choices.size(); ++i)
    if (!s.empty() && s == choices[i]) return int(i);
  place.fail("expected one of " + joinKeys(choices) + ", got " + v.shown);
}

std::string joinKeys(const std::vector<std::string>& keys) {
  std::string out;
  for (auto& k : keys) out += (out.empty() ? "" : ", ") + k;
  return out;
}

}  // namespace penumbra
