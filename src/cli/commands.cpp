#include "cli/commands.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"
#include "core/metrics.h"
#include "pipeline/compare.h"
#include "sampling/shared.hpp"
#include "scene/scene.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace penumbra::cli {
namespace {

Scene loadSceneFor(const CommonOptions& o) {
  return o.scene.empty() ? defaultScene(o.overrides) : loadScene(o.scene, o.overrides);
}

RenderSettings settingsFor(const CommonOptions& o, const Scene& scene) {
  RenderSettings s;
  if (o.width == 0 || o.height == 0 || o.width < -1 || o.height < -1)
    throw Error("-W/-H", "image size must be positive", ExitCode::Usage);
  s.width = o.width > 0 ? o.width : scene.width;
  s.height = o.height > 0 ? o.height : scene.height;
  if (o.samples < 1 || o.samples > PENUMBRA_MAX_SAMPLES)
    throw Error("--samples", "must be in 1.." + std::to_string(PENUMBRA_MAX_SAMPLES) + ", got " +
                                 std::to_string(o.samples), ExitCode::Usage);
  s.sampling.count = o.samples;
  s.sampling.strategy = parseSampleStrategy(o.strategy);
  s.sampling.pattern = parsePixelPattern(o.pattern);
  s.sampling.seed = o.seed;
  s.time = o.time;
  s.shading = parseShadingMode(o.shading);
  return s;
}

// Fails before any rendering when `path`'s folder is missing or not writable.
void checkWritableFolder(const fs::path& dir, const std::string& what) {
  fs::path d = dir.empty() ? fs::path(".") : dir;
  std::error_code ec;
  if (!fs::is_directory(d, ec)) throw Error(what, "folder '" + d.string() + "' does not exist");
  if (::access(d.c_str(), W_OK) != 0) throw Error(what, "folder '" + d.string() + "' is not writable");
}

void checkOutputPath(const std::string& path) {
  auto ext = fs::path(path).extension().string();
  if (ext != ".exr" && ext != ".png") throw Error(path, "output must end in .exr or .png", ExitCode::Usage);
  checkWritableFolder(fs::path(path).parent_path(), path);
}

}  // namespace

int listTechniques(bool asJson) {
  if (asJson) {
    json j = json::array();
    for (auto& t : techniqueTable()) j.push_back({{"name", t.name}, {"description", t.description}});
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  for (auto& t : techniqueTable()) std::printf("%-20s %s\n", t.name.c_str(), t.description.c_str());
  return 0;
}

int info(const CommonOptions& o) {
  Scene scene = loadSceneFor(o);
  json j;
  j["scene"] = scene.sourcePath.empty() ? "default" : scene.sourcePath;
  j["triangles"] = scene.triangleCount();
  j["lights"] = scene.lights.size();
  j["materials"] = scene.materials.size();
  j["semiOpaque"] = scene.hasSemiOpaque();
  j["warnings"] = scene.warnings;
  json meshes = json::array();
  for (auto& m : scene.meshes) {
    const auto& r = m.report;
    meshes.push_back({{"name", m.name}, {"triangles", r.triangles}, {"inputFaces", r.inputFaces},
                      {"droppedInvalidIndex", r.droppedInvalidIndex}, {"droppedDegenerate", r.droppedDegenerate},
                      {"droppedNonFinite", r.droppedNonFinite}, {"droppedDuplicate", r.droppedDuplicate},
                      {"duplicatedVertices", r.duplicatedVertices}, {"openEdges", r.openEdges},
                      {"nonManifoldEdges", r.nonManifoldEdges}, {"inconsistentEdges", r.inconsistentEdges},
                      {"components", r.components}, {"closed", r.closed}});
  }
  j["meshes"] = meshes;
  if (o.json) {
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  std::printf("scene      %s\n", j["scene"].get<std::string>().c_str());
  std::printf("triangles  %zu\nlights     %zu\nmaterials  %zu%s\n", scene.triangleCount(), scene.lights.size(),
              scene.materials.size(), scene.hasSemiOpaque() ? " (semi-opaque surfaces present)" : "");
  for (auto& m : scene.meshes) std::printf("mesh %-40s %s\n", m.name.c_str(), m.report.summary().c_str());
  for (auto& w : scene.warnings) std::printf("warning    %s\n", w.c_str());
  return 0;
}

int render(const CommonOptions& o, const std::string& technique, const std::string& output) {
  const TechniqueInfo& info = findTechnique(technique);
  checkOutputPath(output);
  Scene scene = loadSceneFor(o);
  RenderSettings settings = settingsFor(o, scene);
  auto context = gl::Context::create(gl::parseBackend(o.backend));
  PLOG_INFO("renderer: {} ({})", context->renderer(), context->version());
  Renderer renderer(*context, scene, settings);
  auto tech = info.create();
  FrameResult frame = renderer.render(*tech);
  writeFrame(output, frame);
  json j = frameSummary(frame);
  j["technique"] = technique;
  j["renderer"] = context->renderer();
  j["output"] = output;
  if (o.json) std::printf("%s\n", j.dump(2).c_str());
  else PLOG_INFO("{}: {:.1f} ms -> {}", technique, frame.timer.total(), output);
  return 0;
}

int compare(const CommonOptions& o, const std::vector<std::string>& names, const std::string& outDir,
            double maxError) {
  std::vector<std::string> techniques;
  if (names.size() == 1 && names[0] == "all") {
    for (auto& t : techniqueTable())
      if (t.name != "raytrace") techniques.push_back(t.name);
  } else {
    for (auto& n : names) techniques.push_back(findTechnique(n).name);
  }
  std::error_code ec;
  fs::create_directories(outDir, ec);
  checkWritableFolder(outDir, outDir);
  Scene scene = loadSceneFor(o);
  RenderSettings settings = settingsFor(o, scene);
  auto context = gl::Context::create(gl::parseBackend(o.backend));
  PLOG_INFO("renderer: {} ({})", context->renderer(), context->version());

  CompareReport report = compareTechniques(*context, scene, settings, techniques, outDir);
  json j = report.json;
  j["backend"] = o.backend;
  std::ofstream(fs::path(outDir) / "report.json") << j.dump(2) << "\n";
  std::ofstream(fs::path(outDir) / "table.txt") << report.table;
  std::fprintf(stderr, "%s", report.table.c_str());
  if (o.json) std::printf("%s\n", j.dump(2).c_str());
  if (maxError >= 0.0) {
    for (auto& [name, rmse] : report.visibilityRmse)
      if (rmse > maxError) {
        std::fprintf(stderr, "penumbra: %s: visibility RMSE %.4g exceeds --max-error %.4g\n", name.c_str(), rmse, maxError);
        return int(ExitCode::ThresholdExceeded);
      }
  }
  return 0;
}

}  // namespace penumbra::cli
