#include "study/plan.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>

#include <fmt/format.h>

#include "core/error.h"
#include "core/files.h"
#include "core/fnv.h"
#include "scene/scene.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace penumbra::study {
namespace {

std::string readWhole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Every string of a JSON document, depth first.
void strings(const json& j, std::vector<std::string>& out) {
  if (j.is_string()) out.push_back(j.get<std::string>());
  if (j.is_array() || j.is_object())
    for (const json& v : j) strings(v, out);
}

// The names a file's text gives other files by: every string of a JSON document (scene files,
// .gltf), or an OBJ's `mtllib` and an MTL's `map_*` lines.
std::vector<std::string> namedFiles(const std::string& path, const std::string& text) {
  std::vector<std::string> names;
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".json" || ext == ".gltf") {
    const json j = json::parse(text, nullptr, false);
    if (!j.is_discarded()) strings(j, names);
  } else if (ext == ".obj" || ext == ".mtl") {
    static const std::regex line(R"(^\s*(mtllib|map_\w+|bump|disp)\s+(.+?)\s*$)");
    std::smatch m;
    std::size_t start = 0;
    while (start < text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      const std::string l = text.substr(start, end - start);
      if (std::regex_match(l, m, line)) names.push_back(m[2]);
      start = end + 1;
    }
  }
  return names;
}

// A job's id hashes its scene by file name and every file it reads by content (the names a scene
// gives its inputs are in its content): the same study and scenes at another path, or at
// another depth, plan the same ids.
std::string hashOf(json row, const std::vector<std::string>& inputs) {
  Fnv1a h;
  row["scene"] = fs::path(row["scene"].get<std::string>()).filename().string();
  const std::string r = row.dump();
  h.bytes(r.data(), r.size());
  for (const std::string& f : inputs) {
    const std::string content = readWhole(f);
    h.bytes(content.data(), content.size());
  }
  const std::string build = buildIdentity();
  h.bytes(build.data(), build.size());
  return hex64(h.h);
}

}  // namespace

const char* buildIdentity() { return PENUMBRA_BUILD_IDENTITY; }

json Job::json() const {
  nlohmann::json j = {{"id", id},         {"kind", kind},         {"scene", scene},      {"technique", technique},
                      {"params", params}, {"samples", samples},   {"width", size.width}, {"height", size.height},
                      {"seed", seed},     {"strategy", strategy}, {"frames", frames},    {"warmup", warmup},
                      {"images", images}};
  if (!variant.empty()) j["variant"] = variant;
  if (lightScale != 1.0) j["lightScale"] = lightScale;
  if (shading != "ratio") j["shading"] = shading;
  if (pattern != "correlated") j["pattern"] = pattern;
  if (!profile.empty()) j["profile"] = profile;
  if (!reference.empty()) j["reference"] = reference;
  if (!converged.empty()) j["converged"] = converged;
  return j;
}

Job Job::fromJson(const nlohmann::json& row, const std::string& where) {
  try {
    Job j;
    j.id = row.at("id").get<std::string>(), j.kind = row.at("kind").get<std::string>();
    j.scene = row.at("scene").get<std::string>(), j.technique = row.at("technique").get<std::string>();
    j.params = row.at("params").get<std::vector<std::string>>();
    j.samples = row.at("samples").get<int>();
    j.size = {row.at("width").get<int>(), row.at("height").get<int>()};
    j.seed = row.at("seed").get<std::uint32_t>(), j.strategy = row.at("strategy").get<std::string>();
    j.frames = row.at("frames").get<int>(), j.warmup = row.at("warmup").get<int>();
    j.images = row.at("images").get<std::string>();
    j.variant = row.value("variant", std::vector<std::string>{});
    j.lightScale = row.value("lightScale", 1.0);
    j.shading = row.value("shading", "ratio"), j.pattern = row.value("pattern", "correlated");
    j.profile = row.value("profile", std::vector<std::string>{});
    j.reference = row.value("reference", ""), j.converged = row.value("converged", "");
    if (j.kind != "technique" && j.kind != "reference" && j.kind != "converged")
      throw Error(where, "a job of unknown kind '" + j.kind + "'", ExitCode::Usage);
    if (j.id.size() != 16 || j.id.find_first_not_of("0123456789abcdef") != std::string::npos)
      throw Error(where, "a job id that is not 16 hex digits: " + abbreviate(j.id), ExitCode::Usage);
    return j;
  } catch (const nlohmann::json::exception& e) {
    throw Error(where, std::string("not a job row: ") + e.what(), ExitCode::Usage);
  }
}

std::vector<Job> readPlan(const std::string& dir) {
  const std::string path = (fs::path(dir) / "jobs.jsonl").string();
  std::ifstream in(path);
  if (!in) throw Error(path, "cannot read the plan (make it with `penumbra study plan STUDY -o DIR`)", ExitCode::Usage);
  std::vector<Job> jobs;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const std::string where = fmt::format("{}:{}", path, n);
    const json row = json::parse(line, nullptr, false);
    if (row.is_discarded()) throw Error(where, "not JSON", ExitCode::Usage);
    jobs.push_back(Job::fromJson(row, where));
  }
  if (jobs.empty()) throw Error(path, "a plan with no jobs", ExitCode::Usage);
  return jobs;
}

std::vector<std::string> sceneInputs(const std::string& scene) {
  if (scene == "default") return {};
  std::vector<std::string> out, queue{fs::weakly_canonical(scene).string()};
  while (!queue.empty()) {
    const std::string f = queue.front();
    queue.erase(queue.begin());
    if (std::find(out.begin(), out.end(), f) != out.end()) continue;
    out.push_back(f);
    const fs::path dir = fs::path(f).parent_path();
    for (const std::string& name : namedFiles(f, readWhole(f))) {
      if (name.empty() || name.find("data:") == 0 || name.size() > 4096) continue;
      std::error_code ec;
      const fs::path p = fs::path(name).is_absolute() ? fs::path(name) : dir / name;
      if (fs::is_regular_file(p, ec)) queue.push_back(fs::weakly_canonical(p, ec).string());
    }
  }
  return out;
}

std::vector<Job> planJobs(const StudySpec& s) {
  std::vector<Job> refs, jobs;
  std::set<std::string> planned;  // ids, so that parts share their common jobs
  const auto add = [&](std::vector<Job>& to, const Job& j) {
    if (planned.insert(j.id).second) to.push_back(j);
  };
  std::map<std::string, std::vector<std::string>> inputsOf;  // scene path -> the files it reads
  for (const StudyAxes& a : s.products())
    for (const SceneEntry& scene : a.scenes) {
      if (!inputsOf.count(scene.path)) try {
          if (scene.path != "default") {
            LoadOptions headers;
            headers.decodeTextures = false;
            loadScene(scene.path, {}, headers);
          }
          inputsOf[scene.path] = sceneInputs(scene.path);
        } catch (const Error& e) {
          throw Error(s.path, fmt::format("scenes: {}: {}", scene.path, e.what()), ExitCode::Usage);
        }
      const auto finish = [&](Job& j) {
        json row = j.json();
        row.erase("id");
        j.id = hashOf(row, inputsOf[scene.path]);
      };
      const auto job = [&](const std::string& kind, const std::string& technique, int samples, const Size& size) {
        Job j;
        j.kind = kind, j.scene = scene.path, j.variant = scene.variant, j.technique = technique;
        j.samples = samples, j.size = size, j.frames = a.frames, j.warmup = a.warmup, j.images = s.images;
        return j;
      };
      for (const Size& size : a.sizes)
        for (double lightScale : a.lightScales) {
          std::string convergedId;
          if (a.converged) {
            Job c = job("converged", "raytrace-converged", a.convergedSamples, size);
            c.seed = 1, c.strategy = "stratified", c.lightScale = lightScale, c.frames = 1, c.warmup = 0;
            finish(c);
            convergedId = c.id;
            add(refs, c);
          }
          for (int n : a.samples)
            for (std::uint32_t seed : a.seeds)
              for (const std::string& strategy : a.strategies)
                for (const std::string& shading : a.shadings)
                  for (const std::string& pattern : a.patterns) {
                    Job r = job("reference", "raytrace", n, size);
                    r.seed = seed, r.strategy = strategy, r.lightScale = lightScale;
                    r.shading = shading, r.pattern = pattern, r.converged = convergedId;
                    finish(r);
                    add(refs, r);
                    for (const TechniqueAxis& t : a.techniques)
                      for (const auto& params : t.paramSets) {
                        Job j = r;
                        j.kind = "technique", j.technique = t.name, j.params = params, j.profile = t.profile;
                        j.reference = r.id;
                        finish(j);
                        add(jobs, j);
                      }
                  }
        }
    }
  refs.insert(refs.end(), jobs.begin(), jobs.end());
  return refs;
}

void writePlan(const std::vector<Job>& jobs, const StudySpec& spec, const std::string& dir) {
  fs::create_directories(dir);
  std::string lines;
  for (const Job& j : jobs) lines += j.json().dump() + "\n";
  writeTextFile((fs::path(dir) / "jobs.jsonl").string(), lines);
  json study = {{"name", spec.name}, {"file", spec.path}, {"jobs", jobs.size()}, {"build", buildIdentity()}};
  writeTextFile((fs::path(dir) / "study.json").string(), study.dump(2) + "\n");
}

}  // namespace penumbra::study
