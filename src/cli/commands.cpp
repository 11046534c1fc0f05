#include "cli/commands.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/files.h"
#include "core/image_io.h"
#include "core/log.h"
#include "core/machine.h"
#include "core/metrics.h"
#include "core/progress.h"
#include "studies.h"
#include "cli/options.h"
#include "compare/compare.h"
#include "compare/report.h"
#include "shared/shared.h"  // NOLINT: shared with GLSL
#include "scene/scene.h"
#include "shading/ltc.h"
#include "shading/prefiltered_light.h"
#include "study/merge.h"
#include "study/plan.h"
#include "study/run.h"
#include "study/study_file.h"
#include "techniques/registry.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace penumbra::cli {
namespace {

Scene loadSceneFor(const CommonOptions& o, const LoadOptions& load = {}) {
  return o.scene.empty() ? defaultScene(o.overrides, load) : loadScene(o.scene, o.overrides, load);
}

// Numbers CLI11 reads as floats accept "nan" and "inf": refused here, one line, exit 2.
void checkTime(float time) {
  if (!std::isfinite(time))
    throw Error("--time", fmt::format("must be a finite number of seconds, got {}", time), ExitCode::Usage);
}

RenderSettings settingsFor(const CommonOptions& o, const Scene& scene) {
  checkTime(o.time);
  RenderSettings s;
  if ((o.width && *o.width < 1) || (o.height && *o.height < 1))
    throw Error(
        "-W/-H",
        fmt::format("image size must be positive, got {} x {}", o.width ? std::to_string(*o.width) : "the scene's",
                    o.height ? std::to_string(*o.height) : "the scene's"),
        ExitCode::Usage);
  s.width = o.width.value_or(scene.width);
  s.height = o.height.value_or(scene.height);
  if (o.samples < 1 || o.samples > PENUMBRA_MAX_SAMPLES)
    throw Error("--samples",
                "must be in 1.." + std::to_string(PENUMBRA_MAX_SAMPLES) + ", got " + std::to_string(o.samples),
                ExitCode::Usage);
  s.sampling.count = o.samples;
  s.sampling.strategy = parseSampleStrategy(o.strategy);
  s.sampling.pattern = parsePixelPattern(o.pattern);
  s.sampling.seed = o.seed;
  s.time = o.time;
  s.shading = parseShadingMode(o.shading);
  s.interleaveFilter = !o.noInterleaveFilter;
  return s;
}

// Fails before any rendering when folder `dir` is missing, is not a folder, or is not writable;
// `create`: a missing folder (and its parents) is created first, as compare, lut and bench do.
void checkWritableFolder(const fs::path& dir, const std::string& what, bool create = false) {
  fs::path d = dir.empty() ? fs::path(".") : dir;
  std::error_code ec;
  fs::file_status st = fs::status(d, ec);
  if (st.type() == fs::file_type::not_found && create) {
    fs::create_directories(d, ec);
    // A component above it that is a file: say so rather than "does not exist".
    if (ec) throw Error(what, "cannot create folder '" + d.string() + "': " + ec.message());
    st = fs::status(d, ec);
  }
  if (st.type() == fs::file_type::not_found) throw Error(what, "folder '" + d.string() + "' does not exist");
  if (st.type() != fs::file_type::directory) {
    const char* kind = st.type() == fs::file_type::regular ? "a file" : "a device, socket or pipe";
    throw Error(what, "'" + d.string() + "' is " + kind + ", not a folder");
  }
  if (::access(d.c_str(), W_OK) != 0) throw Error(what, "folder '" + d.string() + "' is not writable");
}

// The GL's largest texture bounds the image (the Renderer refuses a larger one too, without
// naming the flag).
void checkImageSize(const gl::Context& context, const RenderSettings& s) {
  const int maxSize = context.maxTextureSize();
  if (s.width > maxSize || s.height > maxSize)
    throw Error("-W/-H",
                "image size " + std::to_string(s.width) + "x" + std::to_string(s.height) + " outside 1.." +
                    std::to_string(maxSize),
                ExitCode::Usage);
}

void checkOutputPath(const std::string& path) {
  auto ext = fs::path(path).extension().string();
  if (ext != ".exr" && ext != ".png") throw Error(path, "output must end in .exr or .png", ExitCode::Usage);
  checkWritableFolder(fs::path(path).parent_path(), path);
}

}  // namespace

namespace {
// The family of a technique: its name up to the first '-' ("pcss-mask" -> "pcss").
std::string familyOf(const std::string& name) { return name.substr(0, name.find('-')); }

// `names` (in table order) shortened: a family of several techniques that all appear is "family*".
std::string shortNames(const std::vector<std::string>& names) {
  std::vector<std::string> out, done;
  for (auto& t : techniqueTable()) {
    const std::string f = familyOf(t.name);
    if (std::find(done.begin(), done.end(), f) != done.end()) continue;
    done.push_back(f);
    std::vector<std::string> members, in;
    for (auto& u : techniqueTable())
      if (familyOf(u.name) == f) members.push_back(u.name);
    for (auto& m : members)
      if (std::find(names.begin(), names.end(), m) != names.end()) in.push_back(m);
    if (in.size() == members.size() && members.size() > 1)
      out.push_back(f + "*");
    else
      out.insert(out.end(), in.begin(), in.end());
  }
  return fmt::format("{}", fmt::join(out, ", "));
}

// docs/cli.md's table of technique parameters (between the technique-params markers;
// tests/generated_tables_test.sh checks they are equal): one row per parameter declaration (key,
// values, meaning), the techniques declaring it and their defaults.
std::string paramsMarkdown(const std::vector<TechniqueInfo>& techniques) {
  struct Row {
    const ParamSpec* spec;
    std::vector<std::string> techniques;
    std::vector<std::pair<std::string, std::vector<std::string>>> defaults;  // default -> techniques
  };
  std::vector<Row> rows;
  for (auto& t : techniques)
    for (auto& p : t.params) {
      auto row = std::find_if(rows.begin(), rows.end(), [&](const Row& r) {
        return r.spec->key == p.key && r.spec->meaning == p.meaning && r.spec->rangeText() == p.rangeText();
      });
      if (row == rows.end()) row = rows.insert(rows.end(), Row{&p, {}, {}});
      row->techniques.push_back(t.name);
      auto d =
          std::find_if(row->defaults.begin(), row->defaults.end(), [&](auto& e) { return e.first == p.defaultText(); });
      if (d == row->defaults.end()) d = row->defaults.insert(row->defaults.end(), {p.defaultText(), {}});
      d->second.push_back(t.name);
    }
  if (rows.empty()) return "(no parameters)\n";
  std::string out = "| key | techniques | default | values | meaning |\n|---|---|---|---|---|\n";
  for (auto& r : rows) {
    std::string defaults;
    for (auto& [value, names] : r.defaults)
      defaults +=
          (defaults.empty() ? "" : ", ") + value + (r.defaults.size() > 1 ? " (" + shortNames(names) + ")" : "");
    auto cell = [](std::string s) {  // a '|' inside a cell is escaped (GitHub tables)
      for (std::size_t p = s.find('|'); p != std::string::npos; p = s.find('|', p + 2)) s.insert(p, "\\");
      return s;
    };
    out += fmt::format("| `{}` | {} | {} | {} | {} |\n", r.spec->key, shortNames(r.techniques), cell(defaults),
                       cell(r.spec->rangeText()), cell(r.spec->meaning));
  }
  return out;
}
}  // namespace

int listTechniques(bool asJson, bool withParams, const std::string& format, const std::vector<std::string>& names) {
  if (format != "text" && format != "markdown" && format != "json")
    throw Error("--format", "expected text, markdown or json, got '" + format + "'", ExitCode::Usage);
  const std::vector<TechniqueInfo> techniques = names.empty() ? techniqueTable() : findTechniques(names);
  if (asJson || format == "json") {
    json j = json::array();
    for (auto& t : techniques) {
      json e = {{"name", t.name}, {"family", toString(t.family)}, {"description", t.description}};
      if (withParams) {
        e["params"] = json::array();
        for (auto& p : t.params)
          e["params"].push_back(
              {{"key", p.key}, {"default", p.defaultText()}, {"values", p.rangeText()}, {"meaning", p.meaning}});
      }
      j.push_back(e);
    }
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  if (format == "markdown") {  // README's technique table; with --params, docs/cli.md's parameter table
    if (withParams) {
      std::printf("%s", paramsMarkdown(techniques).c_str());
      return 0;
    }
    std::printf("| name | family | what |\n|---|---|---|\n");
    for (auto& t : techniques)
      std::printf("| `%s` | %s | %s |\n", t.name.c_str(), toString(t.family), t.description.c_str());
    return 0;
  }
  for (auto& t : techniques) {
    std::printf("%-20s %s\n", t.name.c_str(), t.description.c_str());
    if (!withParams) continue;
    for (auto& p : t.params)
      std::printf("    %-18s %-22s %-24s %s\n", p.key.c_str(), p.defaultText().c_str(), p.rangeText().c_str(),
                  p.meaning.c_str());
  }
  return 0;
}

int info(const CommonOptions& o) {
  Scene scene = loadSceneFor(o, LoadOptions{/*decodeTextures=*/false});  // sides from headers, no pixels
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
    meshes.push_back({{"name", m.name},
                      {"triangles", r.triangles},
                      {"inputFaces", r.inputFaces},
                      {"droppedInvalidIndex", r.droppedInvalidIndex},
                      {"droppedDegenerate", r.droppedDegenerate},
                      {"droppedNonFinite", r.droppedNonFinite},
                      {"droppedDuplicate", r.droppedDuplicate},
                      {"duplicatedVertices", r.duplicatedVertices},
                      {"openEdges", r.openEdges},
                      {"nonManifoldEdges", r.nonManifoldEdges},
                      {"inconsistentEdges", r.inconsistentEdges},
                      {"components", r.components},
                      {"closed", r.closed}});
  }
  j["meshes"] = meshes;
  json textures = json::array();
  for (const Texture& t : scene.textures)
    textures.push_back({{"source", t.source}, {"width", t.width}, {"height", t.height}});
  j["textures"] = textures;
  if (o.json) {
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  std::printf("scene      %s\n", j["scene"].get<std::string>().c_str());
  std::printf("triangles  %zu\nlights     %zu\nmaterials  %zu%s\n", scene.triangleCount(), scene.lights.size(),
              scene.materials.size(), scene.hasSemiOpaque() ? " (semi-opaque surfaces present)" : "");
  for (auto& m : scene.meshes) std::printf("mesh %-40s %s\n", m.name.c_str(), m.report.summary().c_str());
  for (const Texture& t : scene.textures) std::printf("texture    %s (%d x %d)\n", t.source.c_str(), t.width, t.height);
  for (auto& w : scene.warnings) std::printf("warning    %s\n", w.c_str());
  return 0;
}

int render(const CommonOptions& o, const std::string& technique, const std::string& output) {
  const TechniqueInfo& info = findTechnique(technique);
  checkOutputPath(output);
  checkTime(o.time);
  Scene scene = loadSceneFor(o);
  if (scene.isAnimated()) scene = scene.posedAt(o.time);  // "spin": the pose at --time
  scene.makeCameraRelative();                             // in place: the Renderer would otherwise translate a copy
  RenderSettings settings = settingsFor(o, scene);
  // Parameters are read (and refused) before any GL work, as compare does.
  TechniqueParams params(o.params);
  auto tech = makeTechnique(info.name, params);
  params.checkConsumed();
  auto context = gl::Context::create(parseBackend(o.backend));
  PLOG_INFO("renderer: {} ({})", context->renderer(), context->version());
  checkImageSize(*context, settings);
  Renderer renderer(*context, scene, settings);
  // (a shading mode the technique cannot feed is refused by the renderer, naming it)
  FrameResult frame = renderer.render(*tech, technique);
  writeFrame(output, frame);
  json j = frameSummary(frame);
  j["technique"] = technique;
  j["renderer"] = context->renderer();
  j["output"] = output;
  if (o.json)
    std::printf("%s\n", j.dump(2).c_str());
  else
    PLOG_INFO("{}: {:.1f} ms (harness {:.1f} ms apart) -> {}", technique, frame.timer.total(),
              frame.timer.harnessTotal(), output);
  return 0;
}

int compare(const CommonOptions& o, const CompareCliOptions& c) {
  CompareOptions options;
  options.reference = findTechnique("raytrace");
  options.convergedReference = findTechnique("raytrace-converged");
  for (std::size_t i = 0; i < c.techniques.size(); ++i) {
    if (c.techniques[i] == "all" && c.techniques.size() > 1)
      throw Error("--techniques", "'all' is every technique and stands alone (got it with others)", ExitCode::Usage);
    if (std::find(c.techniques.begin(), c.techniques.begin() + std::ptrdiff_t(i), c.techniques[i]) !=
        c.techniques.begin() + std::ptrdiff_t(i))
      throw Error("--techniques", "'" + abbreviate(c.techniques[i]) + "' given twice", ExitCode::Usage);
  }
  if (c.techniques.size() == 1 && c.techniques[0] == "all") {
    for (auto& t : techniqueTable())
      if (t.name != options.reference.name) options.techniques.push_back(t);
  } else {
    options.techniques = findTechniques(c.techniques);
  }
  if (options.techniques.empty()) throw Error("--techniques", "no technique given", ExitCode::Usage);
  for (auto& s : c.sweeps) options.sweeps.push_back(parseSweep(s));
  for (auto& s : c.insets) options.insets.push_back(parseInset(s));
  if (c.timingFrames < 1 || c.timingFrames > 1000)
    throw Error("--timing-frames", "must be in 1..1000", ExitCode::Usage);
  if (c.warmup < 0 || c.warmup > 100) throw Error("--warmup", "must be in 0..100", ExitCode::Usage);
  if (c.frames < 1 || c.frames > 10000) throw Error("--frames", "must be in 1..10000", ExitCode::Usage);
  if (!(c.fps > 0.0f) || !std::isfinite(c.fps)) throw Error("--fps", "must be positive", ExitCode::Usage);
  if (!(c.pixelsPerDegree > 0.0) || !std::isfinite(c.pixelsPerDegree) || c.pixelsPerDegree > 1000.0)
    throw Error("--ppd", fmt::format("must be in (0, 1000] pixels per degree, got {}", c.pixelsPerDegree),
                ExitCode::Usage);
  if (c.maxError && !(std::isfinite(*c.maxError) && *c.maxError >= 0.0))
    throw Error("--max-error", fmt::format("must be a finite RMSE >= 0, got {}", *c.maxError), ExitCode::Usage);
  checkTime(o.time);
  options.params = o.params;
  options.converged = c.converged;
  options.timingFrames = c.timingFrames, options.warmup = c.warmup;
  options.frames = c.frames, options.fps = c.fps;
  options.pixelsPerDegree = c.pixelsPerDegree;

  Scene scene = loadSceneFor(o);
  scene.makeCameraRelative();  // in place: each Renderer would otherwise translate a copy
  RenderSettings settings = settingsFor(o, scene);
  checkComparison(settings, options);  // before the output folder is touched or GL set up
  options.outDir = c.outDir.empty() ? (fs::path("out") / fileNameComponent(scene.name, "scene")).string() : c.outDir;
  checkWritableFolder(options.outDir, options.outDir, /*create=*/true);
  const FolderLock lock(options.outDir);
  removeReport(options.outDir);  // no report of an earlier run beside this run's images
  options.onRow = [&](const CompareResult& partial) { writeReport(partial, options.outDir); };
  auto context = gl::Context::create(parseBackend(o.backend));
  PLOG_INFO("renderer: {} ({})", context->renderer(), context->version());
  checkImageSize(*context, settings);

  CompareResult result = compareTechniques(*context, scene, settings, options);
  result.info["backend"] = o.backend;
  writeReport(result, options.outDir);
  std::fprintf(stderr, "%s", reportTable(result).c_str());
  PLOG_INFO("report: {}", (fs::path(options.outDir) / "index.html").string());
  if (o.json) std::printf("%s\n", result.json().dump(2).c_str());
  // Failed techniques (their rows say why): the run is an error, after the report is written.
  std::vector<std::string> failed;
  std::size_t techniqueRuns = 0;
  for (auto& run : result.runs) techniqueRuns += !run.reference;
  for (auto& run : result.runs)
    if (run.failed) {
      const std::string& label = result.presets[run.preset].label;
      failed.push_back(run.technique + (label.empty() ? "" : " @ " + label) + " (" + run.failure + ")");
    }
  if (!failed.empty())
    throw Error("compare", fmt::format("{} of {} technique runs failed (see the report): {}", failed.size(),
                                       techniqueRuns, fmt::join(failed, "; ")));
  if (c.maxError) {
    for (auto& run : result.runs)
      // A NaN error fails the threshold (the pipeline refuses NaN images; this is the last guard).
      if (!run.reference && !(run.errors.visibility.rmse <= *c.maxError)) {
        std::fprintf(stderr, "penumbra: %s: visibility RMSE %.4g exceeds --max-error %.4g\n", run.technique.c_str(),
                     run.errors.visibility.rmse, *c.maxError);
        return int(ExitCode::ThresholdExceeded);
      }
  }
  return 0;
}

int bench(const BenchOptions& b) {
  const auto& table = bench::studyTable();
  std::vector<const bench::Study*> run;
  if (b.studies.empty()) {
    for (auto& s : table) run.push_back(&s);
  } else {
    for (auto& name : b.studies) {
      auto it = std::find_if(table.begin(), table.end(), [&](auto& s) { return s.name == name; });
      if (it == table.end()) {
        std::string known;
        for (auto& s : table) known += (known.empty() ? "" : ", ") + s.name;
        throw Error("--studies", "unknown study '" + name + "' (known: " + known + ")", ExitCode::Usage);
      }
      run.push_back(&*it);
    }
  }
  const gl::Backend backend = parseBackend(b.backend);
  std::string renderer, version;
  {
    auto context = gl::Context::create(backend);
    renderer = context->renderer(), version = context->version();
  }
  const std::string dir = b.outDir.empty() ? (fs::path("bench/results") / machineName(renderer)).string() : b.outDir;
  checkWritableFolder(dir, dir, /*create=*/true);
  const FolderLock lock(dir);
  const MachineFacts facts = machineFacts();
  const std::string machine = fmt::format(
      "date      {}\ncpu       {}\ncores     {}\nmemory    {}\nos        {}\nrenderer  {}\ngl        {}\nbackend   "
      "{}\nsuite     {}\n",
      utcNow(), facts.cpu, facts.cores, facts.memory, facts.os, renderer, version, b.backend,
      b.quick ? "quick" : "full");
  writeTextFile((fs::path(dir) / "machine.txt").string(), machine);
  PLOG_INFO("bench: {} studies into {} ({})", run.size(), dir, renderer);

  int failed = 0;
  Progress progress(int(run.size()));
  for (const bench::Study* study : run) {
    progress.step(study->name + ": " + study->description);
    fs::path file = fs::path(dir) / (study->name + ".txt");
    std::FILE* out = std::fopen(file.c_str(), "w");
    if (!out) throw Error(file.string(), "cannot write");
    std::fprintf(out, "%s -- %s\nstudy: %s (`penumbra bench%s`, backend %s)\n\n", utcNow().c_str(), renderer.c_str(),
                 study->name.c_str(), b.quick ? " --quick" : "", b.backend.c_str());
    auto t0 = std::chrono::steady_clock::now();
    int rc = study->run({backend, b.quick, dir}, out);
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(out, "\n(study took %.0f s, exit %d)\n", s, rc);
    if (std::fclose(out) != 0) throw Error(file.string(), std::string("cannot write: ") + std::strerror(errno));
    setLogLevel("info");  // studies quieten the log for their own runs
    if (rc != 0) {
      ++failed;
      PLOG_ERROR("bench: study {} failed (exit {}), see {}", study->name, rc, file.string());
    } else {
      PLOG_INFO("bench: {} done in {:.0f} s -> {}", study->name, s, file.string());
    }
  }
  progress.finish();
  return failed ? int(ExitCode::Error) : 0;
}

namespace {

// `lut --ltc`: the fit (all cores; the bytes do not depend on how many), the table and its report.
int ltcLut(const CommonOptions& o, const LutOptions& l) {
  if (l.ltcSize < 2 || l.ltcSize > 256) throw Error("--ltc-size", "must be in 2..256", ExitCode::Usage);
  checkWritableFolder(l.outDir, "--output", /*create=*/true);
  const FolderLock lock(l.outDir);
  shading::LtcFitOptions fit;
  fit.size = l.ltcSize;
  Progress progress(fit.size);
  shading::LtcTable table = shading::fitLtcGgx(fit, {}, [&](int done, int total) {
    progress.step(fmt::format("ltc fit: {} of {} roughness columns", done, total));
  });
  progress.finish();
  const std::string path = (fs::path(l.outDir) / "ltc_ggx.lut").string();
  const std::string report = (fs::path(l.outDir) / "ltc_ggx_error.csv").string();
  shading::writeLtcTable(path, table);
  writeTextFile(report, shading::ltcErrorCsv(table));
  double worst = 0.0, mean = 0.0;
  for (const glm::vec4& t : table.terms) {
    worst = std::max(worst, double(t.z));
    mean += double(t.z) / double(table.terms.size());
  }
  if (o.json) {
    json j = {{"kind", "ltc"}, {"path", path}, {"report", report}, {"mean_l1_error", mean}, {"max_l1_error", worst}};
    std::printf("%s\n", json::array({j}).dump(2).c_str());
  } else {
    std::printf("LTC GGX table %s (%dx%d), per-cell L1 error relative to norm: mean %.4g, max %.4g (%s)\n",
                path.c_str(), fit.size, fit.size, mean, worst, report.c_str());
  }
  return 0;
}

}  // namespace

int lut(const CommonOptions& o, const LutOptions& l) {
  if (l.ltc) return ltcLut(o, l);
  if (l.shape != "rect" && l.shape != "disk")
    throw Error("--shape", "must be rect or disk, got '" + l.shape + "'", ExitCode::Usage);
  if (l.cube < 1 || l.cube > 1024) throw Error("--cube", "must be in 1..1024", ExitCode::Usage);
  if (l.line < 2 || l.line > 4096 || l.line % 2) throw Error("--line", "must be even, in 2..4096", ExitCode::Usage);
  Scene scene;
  if (!o.scene.empty()) {
    scene = loadSceneFor(o);
  } else {
    scene.lights.push_back(patternTables().front().unitLight(l.shape == "rect" ? LightShape::Rect : LightShape::Disk));
  }
  RenderSettings s = settingsFor(o, scene);
  checkWritableFolder(l.outDir, "--output", /*create=*/true);  // after the checks: no folder for a refused run
  const FolderLock lock(l.outDir);
  json written = json::array();
  std::vector<std::string> done;
  // A light's own files, named from the scene's and the light's names (file-name components:
  // core/files.h); two lights whose names come out the same are refused, not overwritten.
  std::map<std::string, std::string> lightFiles;  // path -> light
  const auto lightFile = [&](const Light& light, const std::string& kind) {
    const std::string path = (fs::path(l.outDir) / (fileNameComponent(scene.name, "scene") + "_" +
                                                    fileNameComponent(light.name, "light") + "_" + kind + ".exr"))
                                 .string();
    if (const auto [it, fresh] = lightFiles.emplace(path, light.name); !fresh)
      throw Error("lut", fmt::format("lights '{}' and '{}' would write the same file '{}': give them names that differ "
                                     "in letters or digits",
                                     abbreviate(it->second), abbreviate(light.name), path));
    return path;
  };
  for (const Light& light : scene.lights) {
    LightSampleSet samples = makeLightSamples(scene, light, s.sampling, s.time);
    for (const PatternTable& table : patternTables()) {
      if (!table.supports(light)) {
        PLOG_INFO("lut: light '{}' is not a rect or disk light: no {} LUT ({} uses its exact test)", light.name,
                  table.kind, table.technique);
        continue;
      }
      const std::string path = (fs::path(l.outDir) / table.fileName(samples)).string();
      if (std::find(done.begin(), done.end(), path) != done.end()) continue;
      done.push_back(path);
      table.write(samples, path, l.cube, l.line);
      written.push_back({{"light", light.name}, {"kind", table.kind}, {"path", path}});
    }
    if (!light.emissionFrames.empty()) {
      // DCS paper 7.1: the luminance of each sample, N columns x M sets rows.
      Image lum(samples.count, samples.setCount, 3, 0.0f);
      for (std::size_t i = 0; i < samples.luminance.size(); ++i)
        for (int c = 0; c < 3; ++c) lum.data[i * 3 + std::size_t(c)] = samples.luminance[i][c];
      std::string path = lightFile(light, "luminance");
      writeExr(path, {{"", &lum}});
      written.push_back({{"light", light.name}, {"kind", "luminance"}, {"path", path}});
    }
    if (const Image* texture = lightEmissionTexture(scene, light, s.time);
        texture && (light.shape == LightShape::Rect || light.shape == LightShape::Disk)) {
      // The ratio estimator's prefiltered emission (shading/prefiltered_light.h), a layer a level.
      const shading::PrefilteredLight chain = shading::prefilterLight(*texture, light.shape == LightShape::Disk);
      std::vector<Image> levels(std::size_t(chain.levels), Image(chain.size, chain.size, 4));
      const std::size_t n = std::size_t(chain.size) * std::size_t(chain.size);
      for (std::size_t k = 0; k < levels.size(); ++k)
        std::memcpy(levels[k].data.data(), &chain.texels[k * n].x, n * sizeof(glm::vec4));
      std::vector<ExrLayer> layers;
      for (std::size_t k = 0; k < levels.size(); ++k) layers.push_back({"level" + std::to_string(k), &levels[k]});
      std::string path = lightFile(light, "prefiltered");
      writeExr(path, layers);
      written.push_back({{"light", light.name}, {"kind", "prefiltered"}, {"path", path}});
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

int studyPlan(const StudyPlanOptions& o) {
  const study::StudySpec spec = study::readStudy(o.study);
  checkWritableFolder(o.outDir, "--output", /*create=*/true);
  const std::vector<study::Job> jobs = study::planJobs(spec);
  study::writePlan(jobs, spec, o.outDir);
  std::size_t references = 0;
  for (const study::Job& j : jobs) references += j.kind != "technique";
  std::printf("study %s: %zu jobs (%zu references, %zu technique jobs) -> %s\n", spec.name.c_str(), jobs.size(),
              references, jobs.size() - references, (fs::path(o.outDir) / "jobs.jsonl").string().c_str());
  return 0;
}

int studyRun(const StudyRunOptions& o) {
  study::RunOptions r;
  r.dir = o.dir;
  if (o.index >= 0) r.index = std::size_t(o.index);
  if (!o.shard.empty()) {
    if (o.index >= 0) throw Error("--shard", "give --index or --shard, not both", ExitCode::Usage);
    std::tie(r.shard, r.shards) = parseShard(o.shard);
  }
  if (o.jobs < 1 || o.jobs > 1024)
    throw Error("-j", fmt::format("{}: give 1 to 1024 processes", o.jobs), ExitCode::Usage);
  r.parallel = o.jobs;
  r.force = o.force;
  r.retryFailed = o.retryFailed;
  r.backend = parseBackend(o.backend);
  const study::RunSummary s = study::runStudy(r);
  std::printf("study run: %zu jobs selected: %zu rendered, %zu already done, %zu failed\n", s.selected, s.rendered,
              s.done, s.failed);
  return s.failed > 0 ? int(ExitCode::Error) : 0;
}

int studyMerge(const std::string& dir) {
  const study::MergeSummary s = study::mergeStudy(dir, stdout);
  for (const std::string& r : s.reports) std::printf("report: %s/index.html\n", r.c_str());
  std::printf("results: %s, %s\n", (fs::path(dir) / "results.csv").string().c_str(),
              (fs::path(dir) / "results.jsonl").string().c_str());
  if (s.failed > 0) return int(ExitCode::Error);
  return s.missing > 0 ? int(ExitCode::ThresholdExceeded) : 0;
}

}  // namespace penumbra::cli
