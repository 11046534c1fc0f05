// The explicit name -> factory table of techniques. No static registration: each technique
// folder exports its rows (<folder>Rows() in its rows.cpp: its techniques and presets, their
// parameters and family), and the table is those rows in the order of the one list of folders
// in src/techniques/CMakeLists.txt (which also builds them: registry.cpp includes the list).
// Above the pipeline (pipeline/technique.h), which does not know the table; compare and the
// CLI are handed TechniqueInfo entries from it.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pipeline/technique.h"

namespace penumbra {

const std::vector<TechniqueInfo>& techniqueTable();
// Throws penumbra::Error("technique", ...) listing the known names.
const TechniqueInfo& findTechnique(const std::string& name);
// findTechnique of each name, in order.
std::vector<TechniqueInfo> findTechniques(const std::vector<std::string>& names);
// findTechnique(name).create(params).
std::unique_ptr<Technique> makeTechnique(const std::string& name, const TechniqueParams& params = {});

// A table a technique precomputes per light-sample pattern and reads from disk when it is there
// (dcs's edge LUT, [Forest08] 7.3): `penumbra lut` writes the tables of patternTables().
struct PatternTable {
  std::string kind;       // "edge"
  std::string technique;  // the folder that reads it
  std::function<bool(const Light&)> supports;
  // A light whose world frame is the table's normalised frame: the light of a pattern given without a scene.
  std::function<Light(LightShape)> unitLight;
  // The file name of the table of `samples` (equal for equal patterns), and its writer: the sector
  // table `cube` x `cube` texels a face, the line table `line` x `line`.
  std::function<std::string(const LightSampleSet& samples)> fileName;
  std::function<void(const LightSampleSet& samples, const std::string& path, int cube, int line)> write;
};
const std::vector<PatternTable>& patternTables();

// A row that is a preset of its folder's options: `params` declared with the preset's values as
// defaults, `make` given the arguments read through them and the preset.
template <class Preset>
TechniqueInfo presetRow(std::string name, std::string description, TechniqueFamily family,
                        std::vector<ParamSpec> params, Preset preset,
                        std::unique_ptr<Technique> (*make)(const TechniqueArgs&, Preset)) {
  return {std::move(name), std::move(description), std::move(params),
          [preset, make](const TechniqueArgs& a) { return make(a, preset); }, family};
}

}  // namespace penumbra
