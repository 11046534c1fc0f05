// Option strings of the command line to the typed settings the libraries take: every flag value
// penumbra and the standalone bench binaries read as text is parsed here, and the usage errors
// (exit 2) name the flag. The libraries take enums and structs and never see a flag.
#pragma once

#include <string>
#include <utility>

#include "compare/compare.h"
#include "gl/context.h"
#include "pipeline/renderer.h"
#include "sampling/light_samples.h"

namespace CLI {
class App;
}

namespace penumbra::cli {

gl::Backend parseBackend(const std::string& name);         // "egl" | "osmesa", else Error("--backend")
ShadingMode parseShadingMode(const std::string& s);        // "modulate" | "per-sample", else Error("--shading")
SampleStrategy parseSampleStrategy(const std::string& s);  // "stratified|poisson|vogel", else Error("--strategy")
PixelPattern parsePixelPattern(const std::string& s);  // "correlated|decorrelated|interleaved", else Error("--pattern")

// One --sweep axis: "key=v1,v2,..."; `samples` and `resolution` values must be integers in
// 1..PENUMBRA_MAX_SAMPLES and 1..16384. Throws Error("--sweep") (usage).
SweepAxis parseSweep(const std::string& arg);
// "x,y,w,h"; throws Error("--inset") (usage).
Inset parseInset(const std::string& arg);

// "i/N" (0 <= i < N, N >= 1): a study run's shard; throws Error("--shard") (usage).
std::pair<int, int> parseShard(const std::string& text);

// A size in bytes: a decimal number and a binary unit, "512MiB", "1.5GiB" (KiB, MiB, GiB, TiB).
// Throws Error(what) (usage).
double parseByteSize(const std::string& what, const std::string& text);

// Every number option of `app` and its subcommands takes decimal numbers only: CLI11 reads
// integers with strtoll's base 0 ("0x10" is 16, "010" is 8) and floats with strtold ("0x1p4",
// "inf"), none of which a user means.
void requireDecimalNumbers(CLI::App& app);

// The flag that sets a field the libraries name in an Error's `where` ("param", "sweep",
// "override", "technique", "samples"), for `subcommand`; "" for a field no flag sets (a file, a
// scene object, a technique). The libraries never name flags: this table is where fields meet them.
std::string flagFor(const std::string& field, const std::string& subcommand);

// An integer in 1..hi, else Error(what, "expected an integer in 1..hi, got 'v'") (usage).
int parsePositive(const std::string& what, const std::string& v, int hi);

}  // namespace penumbra::cli
