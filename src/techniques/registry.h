// The explicit name -> factory table of techniques (registry.cpp). No static registration: a
// technique is added there and nowhere else. Above the pipeline (pipeline/technique.h), which
// does not know the table; compare and the CLI are handed TechniqueInfo entries from it.
#pragma once

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

}  // namespace penumbra
