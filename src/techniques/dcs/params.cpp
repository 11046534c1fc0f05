// dcs's parameters (dcs.h): their one declaration (ParamSpec, the `--param` keys, defaults,
// ranges and meanings that `penumbra list --params` and docs/cli.md's table show) and their reading
// into DcsOptions.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "techniques/dcs/dcs_modes.hpp"
#include "techniques/dcs/dcs.h"
#include "techniques/dcs/packing.h"
#include "techniques/common/shadow_volume/shadow_volume.h"

namespace penumbra {

namespace {
const std::vector<std::string> kSilhouetteChoices = {"accurate", "standard"};
const std::vector<std::string> kCoverageChoices = {"exact", "naive", "lut"};  // PENUMBRA_DCS_COVERAGE_*
const std::vector<std::string> kPathChoices = {"raster", "compute"};
const std::vector<std::string> kOpacityChoices = {"sum", "product"};  // dcs::OpacityMode
std::vector<std::string> baseChoices() {
  std::vector<std::string> out;
  for (const auto& l : dcs::kLayouts) out.push_back(std::to_string(l.base));
  return out;
}
}  // namespace

std::vector<ParamSpec> dcsParams(const DcsOptions& o) {
  return {
      ParamSpec::choice("silhouettes", kSilhouetteChoices[o.silhouettes == SilhouetteMode::Accurate ? 0 : 1],
                        kSilhouetteChoices,
                        "potential silhouette edges: accurate (a silhouette from some point of the light, exact) or "
                        "standard (from the light centre, DCS paper Fig. 4; misses edges)"),
      ParamSpec::boolean("gpu-silhouettes", o.gpuSilhouettes,
                         "accurate silhouettes by a compute shader (src/techniques/dcs/shaders/dcs_silhouette.comp) "
                         "instead of the CPU"),
      ParamSpec::choice("path", kPathChoices[o.computePath ? 1 : 0], kPathChoices,
                        "the wedge pass: raster (each edge's wedge solid rasterised, its front faces depth-tested) or "
                        "compute (wedges binned into 8x8 tiles by the bounds of their visible points and evaluated "
                        "per pixel inside the solid; counts added once, so the packing holds the final counts with "
                        "no partial sums to keep exact: 4 counters a channel on the engine where the raster path's "
                        "later frames fit 3 at 64 samples)"),
      ParamSpec::boolean("end-planes", o.endPlanes,
                         "raster path: each wedge solid cut by the planes of the cones its light part casts from the "
                         "edge's ends (fewer fragments where a large light meets a short edge; engine 256^2: 28.5 M -> "
                         "8.8 M) or drawn with one side plane at each end"),
      ParamSpec::choice("coverage", kCoverageChoices[std::size_t(o.coverage)], kCoverageChoices,
                        "covered-sample test: exact (3D, per sample), naive (the paper's loop over 8-bit packed "
                        "positions, 7.1) or lut (the paper's edge LUT, 7.3); the 2D modes serve rect and disk lights, "
                        "others use exact"),
      ParamSpec::choice(
          "opacity", kOpacityChoices[o.opacity == dcs::OpacityMode::Sum ? 0 : 1], kOpacityChoices,
          "semi-opaque occluders: the product of transmittances or the paper's saturated sum of opacities"),
      ParamSpec::number("opacity-tolerance", o.opacityTolerance, 1e-6, 0.25,
                        "the largest single-layer transmittance error the unit coding may make (dcs/opacity.h)")
          .shown("1/1024"),
      ParamSpec::integer("targets", o.maxTargets, 1, PENUMBRA_DCS_MAX_TARGETS,
                         "packed RGBA32F counter targets per pass (the paper's 4)"),
      ParamSpec::choice("min-base", std::to_string(o.minBase), baseChoices(),
                        "narrowest counter base the packing may use (5.3: more counters per channel, fewer passes)"),
      ParamSpec::integer(
          "first-bound", o.firstFrameBound, 0, int(dcs::kLayouts[dcs::kLayoutCount - 1].base) - 1,
          "a light's first frame plans its counters from this bound instead of the widest base at base "
          "256's cost (the check after the pass and the re-render still apply; tests force them with it)")
          .shown("base 256's cost"),
      ParamSpec::integer("first-reach", o.firstFrameReach, 0, int(dcs::kLayouts[dcs::kLayoutCount - 1].base) - 1,
                         "with first-bound: the partial counts that first frame plans for, above the final ones (the "
                         "plan later frames of exact counts make; tests force a count past its digit with it)")
          .shown("first-bound"),
      ParamSpec::path("lut-file",
                      "the edge LUT file (refused unless built for the light's sample pattern); empty: "
                      "`<lut-dir>/edge_<shape>_<strategy>_<pattern>_n<N>_seed<S>.lut` if it exists, else "
                      "built in memory"),
      ParamSpec::path("lut-dir", "where dcs looks for edge LUTs; empty: the source tree's `luts/`"),
      ParamSpec::integer("lut-cube", o.lutSize.cube, 1, 1024,
                         "sector table size of an edge LUT built in memory (texels "
                         "per cube face side)"),
      ParamSpec::integer("lut-line", o.lutSize.line, 2, 4096, "line table size of an edge LUT built in memory (even)"),
      ParamSpec::boolean("profile", o.profile,
                         "count where the wedge pass's fragments go (statistics `profile*`; slower). A debugging aid, "
                         "also on with the environment variable `PENUMBRA_DCS_PROFILE=1`"),
      bandBytesParam(),
  };
}

DcsOptions readDcsOptions(const TechniqueArgs& args) {
  auto index = [](const std::vector<std::string>& choices, const std::string& v) {
    return int(std::find(choices.begin(), choices.end(), v) - choices.begin());
  };
  DcsOptions o;
  o.silhouettes = args.text("silhouettes") == "accurate" ? SilhouetteMode::Accurate : SilhouetteMode::Standard;
  o.gpuSilhouettes = args.boolean("gpu-silhouettes");
  o.computePath = args.text("path") == "compute";
  o.endPlanes = args.boolean("end-planes");
  o.coverage = index(kCoverageChoices, args.text("coverage"));
  o.opacity = args.text("opacity") == "sum" ? dcs::OpacityMode::Sum : dcs::OpacityMode::Product;
  o.opacityTolerance = args.number("opacity-tolerance");
  o.maxTargets = args.integer("targets");
  o.minBase = std::uint32_t(std::stoul(args.text("min-base")));
  o.firstFrameBound = args.integer("first-bound");
  o.firstFrameReach = args.integer("first-reach");
  o.lutFile = args.text("lut-file");
  o.lutDirectory = args.text("lut-dir");
  // Refused here, before any GL work: a LUT named for a mode that reads none (it was accepted and
  // ignored), a file or folder that is not there (a missing folder fell back to a LUT built in
  // memory without a word).
  if (o.coverage == PENUMBRA_DCS_COVERAGE_EXACT && (!o.lutFile.empty() || !o.lutDirectory.empty()))
    throw Error("param",
                std::string(o.lutFile.empty() ? "lut-dir" : "lut-file") +
                    ": this dcs counts with the exact coverage test and reads no edge LUT (dcs-lut and "
                    "dcs-naive read one)",
                ExitCode::Usage);
  if (!o.lutFile.empty())
    if (const std::string why = fileProblem(o.lutFile); !why.empty())
      throw Error("param", "lut-file: '" + abbreviate(o.lutFile) + "': " + why, ExitCode::Usage);
  if (!o.lutDirectory.empty() && !std::filesystem::is_directory(o.lutDirectory))
    throw Error("param", "lut-dir: '" + abbreviate(o.lutDirectory) + "' is not a folder", ExitCode::Usage);
  o.lutSize.cube = args.integer("lut-cube");
  o.lutSize.line = args.integer("lut-line");
  if (o.lutSize.line % 2)
    throw Error("param", "lut-line: must be even, got " + std::to_string(o.lutSize.line), ExitCode::Usage);
  o.profile = args.boolean("profile");
  o.bandBytes = readBandBytes(args);
  return o;
}

}  // namespace penumbra
