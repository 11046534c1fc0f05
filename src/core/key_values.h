// One checked reader of key/value settings, shared by the scene loader (the JSON objects of a
// scene file, scene_json.cpp Fields) and the technique parameters (`--param key=value`,
// pipeline/technique.h TechniqueParams): numbers, integers, booleans, strings and choices are
// converted, range-checked and refused in one wording, "<where>: <key>: <problem>". What
// becomes of a key nobody read is the caller's policy: TechniqueParams refuses it, the scene
// loader warns.
#pragma once

#include <string>
#include <vector>

#include "core/error.h"

namespace penumbra {

// A value as written. A JSON scalar has a type; the text of `key=value` has none and reads as
// whatever the key asks for (a number by the one parser below, a boolean as true/false/1/0/
// on/off, a string or choice as itself).
struct KeyValue {
  enum class Kind { Number, Integer, Boolean, String, Text, Other };
  Kind kind = Kind::Other;
  double number = 0.0;   // Number, Integer
  bool boolean = false;  // Boolean
  std::string text;      // String: its content; Text: as given
  std::string shown;     // as written, for messages (JSON: its dump; text: quoted)

  static KeyValue ofText(const std::string& text);
};

// Where a value sits: errors are Error(where, at + ": " + problem, code).
struct KeyPlace {
  std::string where;  // the file or field ("scenes/a.json", "param")
  std::string at;     // the key, with its object path ("lights[0].size", "map")
  ExitCode code = ExitCode::Error;
  [[noreturn]] void fail(const std::string& problem) const;
};

// The one text-to-number parser: true when the whole text is a number (strtod's syntax, no
// leading space); one beyond a double's range reads as infinite (callers refuse non-finite).
bool parseNumber(const std::string& text, double& x);

// A finite number in [lo, hi].
double readNumber(const KeyValue& v, const KeyPlace& place, double lo, double hi);
// An integer in [lo, hi] (a JSON integer, or text that parses to a whole number).
int readInteger(const KeyValue& v, const KeyPlace& place, int lo, int hi);
bool readBoolean(const KeyValue& v, const KeyPlace& place);
std::string readString(const KeyValue& v, const KeyPlace& place);
// One of `choices` (a string, or text; JSON numbers too when the choices are numerals): its index.
int readChoice(const KeyValue& v, const KeyPlace& place, const std::vector<std::string>& choices);

// "a, b, c"
std::string joinKeys(const std::vector<std::string>& keys);

}  // namespace penumbra
