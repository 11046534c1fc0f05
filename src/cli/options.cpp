#include "cli/options.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <fmt/format.h>

#include "core/error.h"
#include "core/key_values.h"
#include "shared/shared.h"  // NOLINT: shared with GLSL

namespace penumbra::cli {

namespace {
// The value of `text` in `table`, else a usage error naming `flag`, `what` and the choices.
template <class E, std::size_t N>
E parseNamed(const Named<E> (&table)[N], const std::string& text, const char* flag, const char* what) {
  if (const std::optional<E> value = valueNamed(table, text)) return *value;
  throw Error(flag, fmt::format("unknown {} '{}' ({})", what, abbreviate(text), namesOf(table, ", ")), ExitCode::Usage);
}
}  // namespace

gl::Backend parseBackend(const std::string& name) {
  return parseNamed(gl::kBackendNames, name, "--backend", "backend");
}

ShadingMode parseShadingMode(const std::string& s) {
  return parseNamed(kShadingModeNames, s, "--shading", "shading mode");
}

SampleStrategy parseSampleStrategy(const std::string& s) {
  return parseNamed(kSampleStrategyNames, s, "--strategy", "sampling strategy");
}

PixelPattern parsePixelPattern(const std::string& s) {
  return parseNamed(kPixelPatternNames, s, "--pattern", "pixel pattern");
}

std::string flagFor(const std::string& field, const std::string& subcommand) {
  if (field == "technique") return subcommand == "compare" ? "--techniques" : "--technique";
  static const std::pair<const char*, const char*> kFlags[] = {{"param", "--param"},
                                                               {"sweep", "--sweep"},
                                                               {"override", "--set"},
                                                               {"samples", "--samples"},
                                                               {"reference-samples", "--param reference-samples"},
                                                               {"index", "--index"},
                                                               {"shard", "--shard"}};
  for (const auto& [name, flag] : kFlags)
    if (field == name) return flag;
  return {};
}

std::pair<int, int> parseShard(const std::string& text) {
  int i = -1, n = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &extra) != 2 || n < 1 || i < 0 || i >= n ||
      text.find_first_not_of("0123456789/") != std::string::npos)
    throw Error("--shard", "'" + abbreviate(text) + "': give i/N with 0 <= i < N (\"0/4\" is the first of four)",
                ExitCode::Usage);
  return {i, n};
}

double parseByteSize(const std::string& what, const std::string& text) {
  static const std::pair<const char*, double> kUnits[] = {
      {"KiB", 1024.0}, {"MiB", 1048576.0}, {"GiB", 1073741824.0}, {"TiB", 1099511627776.0}};
  for (const auto& [unit, scale] : kUnits) {
    const std::size_t n = std::char_traits<char>::length(unit);
    double x = 0.0;
    if (text.size() > n && text.compare(text.size() - n, n, unit) == 0 &&
        parseNumber(text.substr(0, text.size() - n), x) && x > 0.0 && x * scale < 1e18)
      return x * scale;
  }
  throw Error(
      what, "expected a positive size with a unit (512MiB, 1.5GiB; KiB, MiB, GiB, TiB), got '" + abbreviate(text) + "'",
      ExitCode::Usage);
}

void requireDecimalNumbers(CLI::App& app) {
  const CLI::Validator decimal(
      [](std::string& text) -> std::string {
        const std::size_t digits = text.find_first_not_of("+-");
        double x = 0.0;
        const bool octalLooking = digits != std::string::npos && text[digits] == '0' && digits + 1 < text.size() &&
                                  std::isdigit(static_cast<unsigned char>(text[digits + 1]));
        return parseNumber(text, x) && !octalLooking ? "" : "expected a decimal number, got '" + abbreviate(text) + "'";
      },
      "DECIMAL");
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    if (type == "INT" || type == "UINT" || type == "FLOAT") option->check(decimal);
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) requireDecimalNumbers(*sub);
}

int parsePositive(const std::string& what, const std::string& v, int hi) {
  std::size_t used = 0;
  long x = 0;
  try {
    x = std::stol(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || x < 1 || x > hi)
    throw Error(what, fmt::format("expected an integer in 1..{}, got '{}'", hi, v), ExitCode::Usage);
  return int(x);
}

namespace {
// "a,b,,c," -> {"a", "b", "", "c", ""}: every empty item kept, so that it is refused (CLI11's
// ->delimiter, used for plain lists, drops a trailing one).
std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out(1);
  for (char c : s) {
    if (c == ',')
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}
}  // namespace

SweepAxis parseSweep(const std::string& arg) {
  auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == arg.size())
    throw Error("--sweep", "expected key=v1,v2,..., got '" + arg + "'", ExitCode::Usage);
  SweepAxis axis{arg.substr(0, eq), splitList(arg.substr(eq + 1)), {}};
  for (auto& v : axis.values)
    if (v.empty()) throw Error("--sweep", "empty value in '" + arg + "'", ExitCode::Usage);
  for (std::size_t i = 0; i < axis.values.size(); ++i)
    for (std::size_t k = 0; k < i; ++k)
      if (axis.values[i] == axis.values[k])
        throw Error("--sweep", axis.key + ": value '" + axis.values[i] + "' given twice", ExitCode::Usage);
  if (axis.key == "samples" || axis.key == "resolution")
    for (auto& v : axis.values)
      axis.integers.push_back(
          parsePositive("--sweep " + axis.key, v, axis.key == "samples" ? PENUMBRA_MAX_SAMPLES : 16384));
  return axis;
}

Inset parseInset(const std::string& arg) {
  auto parts = splitList(arg);
  if (parts.size() != 4) throw Error("--inset", "expected x,y,w,h, got '" + arg + "'", ExitCode::Usage);
  Inset r;
  r.x = parts[0] == "0" ? 0 : parsePositive("--inset", parts[0], 1 << 16);
  r.y = parts[1] == "0" ? 0 : parsePositive("--inset", parts[1], 1 << 16);
  r.w = parsePositive("--inset", parts[2], 1 << 16);
  r.h = parsePositive("--inset", parts[3], 1 << 16);
  return r;
}

}  // namespace penumbra::cli
