// What a comparison writes as it goes: a frame's images (.exr with the visibility layers, .png),
// a run's heat map, unshadowed mask and inset crops, and the JSON of frames, counts and errors.
// The whole run's report (report.json's assembly is CompareResult::json) is compare/report.h.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compare/insets.h"
#include "compare/measure.h"
#include "pipeline/renderer.h"

namespace penumbra {

struct CompareRun;

// Writes .exr (layers: RGB colour, "visibility" for light 0, "visibility1".. for the others)
// or .png (colour, sRGB). Other extensions: penumbra::Error.
void writeFrame(const std::string& path, const FrameResult& frame, float exposure = 0.0f);

// What of a run's frame 0 goes into the output folder.
struct RunImages {
  std::string dir;            // the output folder
  bool exr = true;            // <base>.exr
  bool images = true;         // <base>.png, <base>_heat.png, <base>_unshadowed.png, insets
  std::vector<Inset> insets;  // crops (first preset only: empty for the others)
};
// Writes `frame`'s images as `base` (+ "_heat" against `against`, and "_flip", the FLIP map
// in magma, if given) and records their file names in `run`.
void writeRunImages(const RunImages& out, const std::string& base, const FrameResult& frame, const FrameResult* against,
                    const Image* flip, CompareRun& run);

nlohmann::json frameSummary(const FrameResult& frame);
// {"primitives": .., "vertex": .., "geometry": .., "rasterized": .., "fragment": .., "compute": ..}
nlohmann::json countsJson(const PipelineCounts& c);
nlohmann::json errorsJson(const TechniqueErrors& e);

// A run as CompareResult::json writes it (an element of "runs"), read back: a study merges its
// jobs' rows into the reports a comparison writes (study/merge.h). The preset is the caller's
// (`preset` into its CompareResult::presets); the run's image file names are as written. A row
// that is not such a run: penumbra::Error naming `where`.
CompareRun runFromJson(const nlohmann::json& run, std::size_t preset, const std::string& where);

}  // namespace penumbra
