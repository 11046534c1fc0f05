#include "study/plan.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>

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

std::string hashOf(const json& row, const std::vector<std::string>& inputs) {
  Fnv1a h;
  const std::string r = row.dump();
  h.bytes(r.data(), r.size());
  for (const std::string& f : inputs) {
    const std::string content = readWhole(f);
    h.bytes(f.data(), f.size());
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
  for (const std::string& scene : s.scenes) {
    std::vector<std::string> inputs;
    try {
      if (scene != "default") {
        LoadOptions headers;
        headers.decodeTextures = false;
        loadScene(scene, {}, headers);
      }
      inputs = sceneInputs(scene);
    } catch (const Error& e) {
      throw Error(s.path, fmt::format("scenes: {}: {}", scene, e.what()), ExitCode::Usage);
    }
    const auto finish = [&](Job& j) {
      json row = j.json();
      row.erase("id");
      j.id = hashOf(row, inputs);
    };
    std::map<int, std::string> convergedOf;  // size index -> the converged reference's id
    for (std::size_t z = 0; z < s.sizes.size() && s.converged; ++z) {
      Job c{"", "converged", scene,   "raytrace-converged", {}, s.convergedSamples, s.sizes[z], 1, "stratified",
            1,  0,           s.images};
      finish(c);
      convergedOf[int(z)] = c.id;
      refs.push_back(c);
    }
    for (std::size_t z = 0; z < s.sizes.size(); ++z)
      for (int n : s.samples)
        for (std::uint32_t seed : s.seeds)
          for (const std::string& strategy : s.strategies) {
            Job r{"", "reference", scene, "raytrace", {}, n, s.sizes[z], seed, strategy, s.frames, s.warmup, s.images};
            if (s.converged) r.converged = convergedOf[int(z)];
            finish(r);
            refs.push_back(r);
            for (const TechniqueAxis& t : s.techniques)
              for (const auto& params : t.paramSets) {
                Job j{"",         "technique", scene,    t.name,   params,   n,
                      s.sizes[z], seed,        strategy, s.frames, s.warmup, s.images};
                j.reference = r.id;
                j.converged = r.converged;
                finish(j);
                jobs.push_back(j);
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
