// The table of techniques: every folder's rows, in the order of the list of folders in
// src/techniques/CMakeLists.txt (folders.h, generated from it, declares <folder>Rows() and
// lists them). Adding a technique is its folder and its line in that list.
#include "techniques/registry.h"

#include "core/error.h"
#include "folders.h"

namespace penumbra {

const std::vector<TechniqueInfo>& techniqueTable() {
  static const std::vector<TechniqueInfo> table = [] {
    std::vector<TechniqueInfo> rows;
    for (auto folderRows : kTechniqueFolders)
      for (auto& row : folderRows()) rows.push_back(std::move(row));
    return rows;
  }();
  return table;
}

const TechniqueInfo& findTechnique(const std::string& name) {
  std::string known;
  for (auto& t : techniqueTable()) {
    if (t.name == name) return t;
    known += (known.empty() ? "" : ", ") + t.name;
  }
  throw Error("technique", "unknown technique '" + name + "' (known: " + known + ")", ExitCode::Usage);
}

std::vector<TechniqueInfo> findTechniques(const std::vector<std::string>& names) {
  std::vector<TechniqueInfo> out;
  for (auto& n : names) out.push_back(findTechnique(n));
  return out;
}

PatternTable dcsEdgeLutTable();  // dcs/rows.cpp

const std::vector<PatternTable>& patternTables() {
  static const std::vector<PatternTable> tables = {dcsEdgeLutTable()};
  return tables;
}

std::unique_ptr<Technique> makeTechnique(const std::string& name, const TechniqueParams& params) {
  return findTechnique(name).make(params);
}

}  // namespace penumbra
