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
#include "techniques/dcs/edge_lut.h"

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
  s.interleaveFilter = !o.noInterleaveFilter;
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
  TechniqueParams params(o.params);
  auto tech = info.create(params);
  params.checkConsumed();
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

  CompareReport report = compareTechniques(*context, scene, settings, techniques, outDir, TechniqueParams(o.params));
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

int lut(const CommonOptions& o, const LutOptions& l) {
  if (l.shape != "rect" && l.shape != "disk") throw Error("--shape", "must be rect or disk, got '" + l.shape + "'", ExitCode::Usage);
  if (l.cube < 1 || l.cube > 1024) throw Error("--cube", "must be in 1..1024", ExitCode::Usage);
  if (l.line < 2 || l.line > 4096 || l.line % 2) throw Error("--line", "must be even, in 2..4096", ExitCode::Usage);
  checkWritableFolder(l.outDir, "--output");
  Scene scene;
  if (!o.scene.empty()) {
    scene = loadSceneFor(o);
  } else {
    scene.lights.push_back(dcs::unitLight(l.shape == "rect" ? LightShape::Rect : LightShape::Disk));
  }
  RenderSettings s = settingsFor(o, scene);
  json written = json::array();
  std::vector<std::string> done;
  for (const Light& light : scene.lights) {
    LightSampleSet samples = makeLightSamples(scene, light, s.sampling, s.time);
    if (dcs::edgeLutSupports(light)) {
      std::string path = (fs::path(l.outDir) / dcs::edgeLutFileName(samples)).string();
      if (std::find(done.begin(), done.end(), path) == done.end()) {
        done.push_back(path);
        dcs::EdgeLut table = dcs::buildEdgeLut(dcs::normalisedSamples(samples), samples.count, samples.setCount,
                                               {l.cube, l.line});
        dcs::writeEdgeLut(path, table);
        written.push_back({{"light", light.name}, {"kind", "edge"}, {"path", path}});
      }
    } else {
      PLOG_INFO("lut: light '{}' is not a rect or disk light: no edge LUT (dcs uses its exact test)", light.name);
    }
    if (!light.emissionFrames.empty()) {
      // DCS paper 7.1: the luminance of each sample, N columns x M sets rows.
      Image lum(samples.count, samples.setCount, 3, 0.0f);
      for (std::size_t i = 0; i < samples.luminance.size(); ++i)
        for (int c = 0; c < 3; ++c) lum.data[i * 3 + std::size_t(c)] = samples.luminance[i][c];
      std::string path = (fs::path(l.outDir) / (scene.name + "_" + light.name + "_luminance.exr")).string();
      writeExr(path, {{"", &lum}});
      written.push_back({{"light", light.name}, {"kind", "luminance"}, {"path", path}});
    }
  }
  if (o.json) {
    std::printf("%s\n", written.dump(2).c_str());
  } else {
    for (auto& w : written)
      std::printf("%s: %s LUT %s\n", w["light"].get<std::string>().c_str(), w["kind"].get<std::string>().c_str(),
                  w["path"].get<std::string>().c_str());
  }
  return 0;
}

}  // namespace penumbra::cli
