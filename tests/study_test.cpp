// Studies as data (study/study_file.h, study/plan.h): a study file is checked as a scene file is
// (one line naming the file, the key and the problem), expands into the jobs its axes multiply
// to, and gives each job an id that changes exactly when the job's row, a file it reads or the
// build changes.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "compare/compare.h"
#include "core/error.h"
#include "study/merge.h"
#include "study/plan.h"
#include "study/study_file.h"

namespace fs = std::filesystem;

namespace penumbra::study {
namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    char name[] = "/tmp/penumbra-study-XXXXXX";
    path = mkdtemp(name);
  }
  ~TempDir() { fs::remove_all(path); }
  std::string write(const std::string& file, const std::string& text) const {
    const fs::path p = path / file;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
};

std::string scenes() { return std::string(PENUMBRA_SOURCE_DIR) + "/scenes"; }

// The tests' study: 2 scenes x 3 techniques x 2 sample counts x 2 seeds.
std::string study(const std::string& extra = "") {
  return R"({"name": "small", "scenes": [")" + scenes() + R"(/hard/23-analytic-square.json", ")" + scenes() +
         R"(/hard/16-contact.json"], "techniques": ["dcs", "pcss", {"name": "smrt", "params": {"rays": 4}}],
             "samples": [8, 16], "seeds": [1, 2], "sizes": [64])" +
         extra + "}";
}

// 1000 seeds x 100 sample counts x 100 sizes of one scene and one technique: 10^7
// configurations, 2 x 10^7 jobs with their references.
std::string huge() {
  std::string seeds, samples, sizes;
  for (int i = 0; i < 1000; ++i) seeds += (i ? "," : "") + std::to_string(i);
  for (int i = 1; i <= 100; ++i) samples += (i > 1 ? "," : "") + std::to_string(i);
  for (int i = 1; i <= 100; ++i) sizes += (i > 1 ? "," : "") + std::to_string(16 * i);
  return R"({"scenes": ["default"], "techniques": ["pcss"], "seeds": [)" + seeds + R"(], "samples": [)" + samples +
         R"(], "sizes": [)" + sizes + "]}";
}

std::string errorOf(const std::string& path) {
  try {
    readStudy(path);
  } catch (const Error& e) {
    EXPECT_EQ(e.exitCode(), ExitCode::Usage) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "accepted " << path;
  return {};
}

TEST(Study, ExpandsIntoOneJobPerConfigurationAndSharedReferences) {
  TempDir dir;
  const StudySpec s = readStudy(dir.write("s.json", study()));
  EXPECT_EQ(s.scenes.size(), 2u);
  EXPECT_EQ(jobCount(s), 2u * 2 * 2 * (3 + 1));
  const std::vector<Job> jobs = planJobs(s);
  ASSERT_EQ(jobs.size(), 32u);
  std::set<std::string> ids, references;
  std::size_t technique = 0;
  for (const Job& j : jobs) {
    ids.insert(j.id);
    if (j.kind == "reference") references.insert(j.id);
    if (j.kind != "technique") continue;
    ++technique;
    EXPECT_TRUE(references.count(j.reference)) << "a technique job names a reference planned before it";
    EXPECT_EQ(j.size.width, 64);
  }
  EXPECT_EQ(technique, 24u);
  EXPECT_EQ(references.size(), 8u);
  EXPECT_EQ(ids.size(), jobs.size()) << "ids are unique";
  writePlan(jobs, s, (dir.path / "plan").string());
  std::ifstream in(dir.path / "plan" / "jobs.jsonl");
  std::size_t lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_EQ(lines, jobs.size());
}

// Sweeps multiply: two values of two parameters are four sets, each with the fixed params.
TEST(Study, SweepsAreTheProductOfTheirValues) {
  TempDir dir;
  const StudySpec s =
      readStudy(dir.write("s.json", R"({"scenes": ["default"], "techniques": [{"name": "pcss", "params": {"map": 512},
                    "sweep": {"blocker-samples": [8, 16], "pcf-samples": [4, 8]}}]})"));
  ASSERT_EQ(s.techniques.size(), 1u);
  ASSERT_EQ(s.techniques[0].paramSets.size(), 4u);
  EXPECT_EQ(s.techniques[0].paramSets[3], (std::vector<std::string>{"map=512", "blocker-samples=16", "pcf-samples=8"}));
  EXPECT_EQ(jobCount(s), 5u) << "one configuration: four technique jobs and their reference";
}

// A job's id is its row's, its scene's files' and the build's: the same plan twice gives the same
// ids; editing a texture the scene names changes the ids of that scene's jobs only.
TEST(Study, IdsChangeExactlyWithWhatAJobReads) {
  TempDir dir;
  const fs::path texture = dir.path / "tex.png";
  fs::copy_file(scenes() + "/textures/stained-glass.png", texture);
  dir.write("textured.json", std::string(R"({"objects": [{"shape": "plane", "size": 4}, {"shape": "box", "size": 1,
      "translate": [0, 1, 0]}], "lights": [{"type": "rect", "position": [0, 3, 0], "normal": [0, -1, 0],
      "size": [1, 1], "texture": "tex.png"}]})"));
  const std::string path =
      dir.write("s.json", R"({"scenes": ["textured.json", ")" + scenes() + R"(/hard/23-analytic-square.json"],
                   "techniques": ["pcss"]})");
  const StudySpec s = readStudy(path);
  const std::vector<Job> first = planJobs(s), again = planJobs(s);
  ASSERT_EQ(first.size(), again.size());
  for (std::size_t i = 0; i < first.size(); ++i) EXPECT_EQ(first[i].id, again[i].id);
  const std::vector<std::string> inputs = sceneInputs((dir.path / "textured.json").string());
  ASSERT_EQ(inputs.size(), 2u);
  EXPECT_EQ(fs::path(inputs[1]).filename(), "tex.png");
  fs::copy_file(scenes() + "/textures/stripes.png", texture, fs::copy_options::overwrite_existing);
  const std::vector<Job> edited = planJobs(s);
  for (std::size_t i = 0; i < first.size(); ++i) {
    const bool textured = fs::path(first[i].scene).filename() == "textured.json";
    EXPECT_EQ(first[i].id != edited[i].id, textured) << first[i].scene << " " << first[i].kind;
  }
}

// Bad study files: one line naming the file, the key and the problem, exit 2; the job count is
// refused before anything is expanded.
TEST(Study, BadFilesAreOneLineErrors) {
  TempDir dir;
  const std::pair<std::string, std::string> cases[] = {
      {study(R"(, "colour": "red")"), "colour: unknown key"},
      {study(R"(, "seeds": [])"), "seeds: must not be empty"},
      {R"({"scenes": ["missing.json"], "techniques": ["dcs"]})", "scenes[0]: no such file"},
      {R"({"scenes": ["nothing-*.json"], "techniques": ["dcs"]})", "matches no file"},
      {R"({"scenes": ["default"], "techniques": [{"name": "pcss", "params": {"map": 7}}]})", "techniques[0]"},
      {R"({"scenes": ["default"], "techniques": ["nope"]})", "unknown technique 'nope'"},
      {R"({"scenes": ["default"], "techniques": ["dcs"], "samples": [8, 100000]})", "samples[1]"},
      {R"({"scenes": ["default"], "techniques": ["dcs"], "strategies": ["sobol"]})", "unknown strategy 'sobol'"},
      {huge(), "expands to 20000000 jobs"},
      {study(R"(, "shadings": ["phong"])"), "shadings[0]: unknown shading mode 'phong'"},
      {study(R"(, "patterns": "diagonal")"), "patterns: unknown pixel pattern 'diagonal'"},
      {study(R"(, "light-scales": [1, 0])"), "light-scales[1]"},
      {R"({"scenes": [{"file": "missing.json"}], "techniques": ["dcs"]})", "scenes[0].file: no such file"},
      {R"({"scenes": [{"file": ")" + scenes() + R"(/semi-opaque.json", "opacity": 2}], "techniques": ["dcs"]})",
       "scenes[0].opacity"},
      {R"({"scenes": [{"file": ")" + scenes() + R"(/semi-opaque.json", "tint": 1}], "techniques": ["dcs"]})",
       "scenes[0].tint: unknown key"},
      {R"({"scenes": ["default"], "techniques": [{"name": "dcs", "profile": {}}]})", "techniques[0].profile"},
      {R"({"scenes": ["default"], "techniques": [{"name": "dcs", "profile": {"frobnicate": 1}}]})", "techniques[0]"},
      {R"({"techniques": ["dcs"], "parts": [{"scenes": "default"}, {"samples": 8}]})", "parts[1].scenes: missing"},
      {R"({"scenes": "default", "techniques": ["dcs"], "parts": [{"sizes": 64, "colour": 1}]})",
       "parts[0].colour: unknown key"},
      {"{\"scenes\": ", "not valid JSON"},
  };
  for (auto& [text, want] : cases) {
    const std::string path = dir.write("bad.json", text);
    const std::string what = errorOf(path);
    EXPECT_NE(what.find(want), std::string::npos) << "got: " << what;
    EXPECT_NE(what.find("bad.json"), std::string::npos) << "names the file: " << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
  }
}

// A study of parts plans the union of their products, a job two parts share once; the axes a
// study leaves at their defaults are not in the rows, the others reach the jobs and read back.
TEST(Study, PartsAreAUnionThatPlansSharedJobsOnce) {
  TempDir dir;
  const std::string semi = scenes() + "/semi-opaque.json";
  const StudySpec s = readStudy(dir.write("s.json", R"({"scenes": "default", "techniques": "dcs", "parts": [
      {"techniques": ["dcs", "pcss"]},
      {"shadings": ["modulate", "ratio"]},
      {"patterns": ["correlated", "interleaved"]},
      {"scenes": [{"file": ")" + semi + R"(", "opacity": 1}]}]})"));
  ASSERT_EQ(s.parts.size(), 4u);
  EXPECT_EQ(jobCount(s), 3u + 4 + 4 + 2) << "an upper bound: the parts' products";
  const std::vector<Job> jobs = planJobs(s);
  // default/ratio/correlated: reference, dcs, pcss; modulate: reference, dcs; interleaved:
  // reference, dcs; the opaque twin: reference, dcs.
  ASSERT_EQ(jobs.size(), 9u);
  std::set<std::string> ids, shadings, patterns;
  for (const Job& j : jobs) {
    ids.insert(j.id);
    shadings.insert(j.shading), patterns.insert(j.pattern);
    const Job back = Job::fromJson(j.json(), "test");
    EXPECT_EQ(back.json(), j.json()) << "a row reads back as itself";
    if (j.scene == semi) {
      EXPECT_EQ(j.variant, std::vector<std::string>{"opacity=1"});
      EXPECT_EQ(j.json().at("variant"), nlohmann::json::array({"opacity=1"}));
    } else {
      EXPECT_FALSE(j.json().contains("variant")) << "a default axis is not in the row";
    }
  }
  EXPECT_EQ(ids.size(), jobs.size());
  EXPECT_EQ(shadings, (std::set<std::string>{"modulate", "ratio"}));
  EXPECT_EQ(patterns, (std::set<std::string>{"correlated", "interleaved"}));
  EXPECT_EQ(s.allScenes().size(), 2u);
}

// Light scales multiply the configurations (the converged reference is one per scale, its
// scene differs); a technique's profile parameters reach its jobs.
TEST(Study, LightScalesAndProfilesReachTheJobs) {
  TempDir dir;
  const StudySpec s = readStudy(dir.write("s.json", R"({"scenes": "default", "samples": [8, 16],
      "techniques": [{"name": "dcs", "params": {"path": "raster"}, "profile": {"profile": true}}],
      "light-scales": [0.5, 2], "reference": {"converged": true}})"));
  const std::vector<Job> jobs = planJobs(s);
  EXPECT_EQ(jobs.size(), jobCount(s));
  ASSERT_EQ(jobs.size(), 2u * (1 + 2 * 2));
  std::map<double, std::string> convergedOf;
  for (const Job& j : jobs) {
    EXPECT_TRUE(j.lightScale == 0.5 || j.lightScale == 2.0) << j.lightScale;
    if (j.kind == "converged") convergedOf[j.lightScale] = j.id;
  }
  ASSERT_EQ(convergedOf.size(), 2u);
  for (const Job& j : jobs) {
    if (j.kind == "converged") continue;
    EXPECT_EQ(j.converged, convergedOf[j.lightScale]) << "each scale's own converged reference";
    if (j.kind == "technique") {
      EXPECT_EQ(j.params, std::vector<std::string>{"path=raster"});
      EXPECT_EQ(j.profile, std::vector<std::string>{"profile=true"});
    }
  }
}

// The ids hash a scene's file name and the content of what it reads, not where it lies: the same
// study and scenes copied to another folder, one deeper, plan the same ids.
TEST(Study, IdsDoNotDependOnWhereTheStudyLies) {
  TempDir tmp;
  std::vector<std::string> ids[2];
  int k = 0;
  for (const fs::path& root : {tmp.path / "a", tmp.path / "b" / "deeper"}) {
    fs::create_directories(root / "scenes");
    fs::create_directories(root / "studies");
    fs::copy_file(scenes() + "/hard/16-contact.json", root / "scenes" / "contact.json");
    std::ofstream(root / "studies" / "s.json") << R"({"scenes": "../scenes/contact.json", "techniques": "pcss"})";
    for (const Job& j : planJobs(readStudy((root / "studies" / "s.json").string()))) ids[k].push_back(j.id);
    ++k;
  }
  EXPECT_EQ(ids[0], ids[1]);
  ASSERT_EQ(ids[0].size(), 2u);
}

// A scene that does not load is refused when the study is planned, naming the study and the scene.
TEST(Study, ASceneThatDoesNotLoadIsRefusedAtPlanTime) {
  TempDir dir;
  dir.write("broken.json", R"({"objects": [{"shape": "sphere", "radius": -1}]})");
  const StudySpec s = readStudy(dir.write("s.json", R"({"scenes": ["broken.json"], "techniques": ["dcs"]})"));
  try {
    planJobs(s);
    ADD_FAILURE() << "planned a scene that does not load";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("s.json"), std::string::npos) << what;
    EXPECT_NE(what.find("broken.json"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace penumbra::study

namespace penumbra::study {
namespace {

// A finished job's row written by hand: one run of `ms` a frame (one stage, "work") with this
// visibility RMSE against the same-sample reference.
void writeHandRow(const std::string& out, const Job& j, double ms, double rmse, const std::string& renderer) {
  CompareResult r;
  r.presets.resize(1);
  CompareRun run;
  run.technique = j.technique, run.reference = j.kind == "reference", run.total = {ms, ms, ms};
  run.stages = {{"work", {ms, ms, ms}}};
  run.statistics = {{"answer", 42}};
  run.errors.visibility.rmse = rmse;
  r.runs = {run};
  nlohmann::json row = j.json();
  row["status"] = "ok", row["result"] = r.json()["runs"][0], row["renderer"] = renderer;
  row["info"] = {{"sceneName", "default"}, {"width", 32}, {"height", 32}};
  row["files"] = nlohmann::json::array();
  fs::create_directories(fs::path(out) / "jobs" / j.id);
  std::ofstream(fs::path(out) / "jobs" / j.id / "row.json") << row.dump();
}

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A merge of hand-written rows (no GL): one scene, pcss against the same-sample reference at two
// seeds. The headline's numbers are the geometric means over the seeds with their range, a
// missing row is named, and rows of another renderer get a report of their own.
TEST(Study, MergeTakesGeometricMeansWithTheSeedsSpread) {
  TempDir dir;
  StudySpec spec = readStudy(dir.write(
      "s.json", R"({"scenes": ["default"], "techniques": ["pcss"], "samples": 8, "sizes": 32, "seeds": [1, 2]})"));
  const std::vector<Job> jobs = planJobs(spec);
  ASSERT_EQ(jobs.size(), 4u);
  const std::string out = (dir.path / "study").string();
  writePlan(jobs, spec, out);
  // Per seed: raytrace 5 / 20 ms, pcss 10 / 40 ms with visibility RMSE 0.01 / 0.04.
  const auto writeRow = [&](const Job& j, double ms, double rmse, const std::string& renderer) {
    writeHandRow(out, j, ms, rmse, renderer);
  };
  for (const Job& j : jobs) {
    const bool second = j.seed == 2;
    writeRow(j, j.kind == "reference" ? (second ? 20 : 5) : (second ? 40 : 10),
             j.kind == "reference" ? 0 : (second ? 0.04 : 0.01), "R");
  }
  std::FILE* sink = std::fopen("/dev/null", "w");
  MergeSummary m = mergeStudy(out, sink);
  EXPECT_EQ(m.ok, 4u);
  EXPECT_EQ(m.missing, 0u);
  std::ifstream md(fs::path(out) / "report" / "headline.md");
  const std::string headline((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(headline.find("| pcss | 8 | 20.0 [10.0, 40.0] | 2.00 [2.00, 2.00] | 0.0200 [0.0100, 0.0400] |"),
            std::string::npos)
      << headline;
  EXPECT_TRUE(fs::exists(fs::path(out) / "report" / "default" / "report.json"));
  std::ifstream csv(fs::path(out) / "results.csv");
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_EQ(lines, 5);

  // A row deleted is missing; a row from another renderer makes a second report.
  fs::remove(fs::path(out) / "jobs" / jobs[3].id / "row.json");
  writeRow(jobs[2], 10, 0.01, "S");
  m = mergeStudy(out, sink);
  EXPECT_EQ(m.missing, 1u);
  EXPECT_EQ(m.reports.size(), 2u);
  std::ifstream status(fs::path(m.reports[0]) / "status.txt");
  const std::string text((std::istreambuf_iterator<char>(status)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("missing  " + jobs[3].id), std::string::npos) << text;
  std::fclose(sink);
}

// A study with light scales: the merge tables and draws each technique's error against the
// scale, per scene; stages.md gives every run's stages, ratio to raytrace and statistics.
TEST(Study, MergeDrawsErrorAgainstLightSizeAndTheStageTables) {
  TempDir dir;
  StudySpec spec = readStudy(dir.write("s.json", R"({"scenes": ["default"], "techniques": ["pcss"], "samples": 8,
      "sizes": 32, "light-scales": [0.5, 1, 2]})"));
  const std::vector<Job> jobs = planJobs(spec);
  ASSERT_EQ(jobs.size(), 6u);
  const std::string out = (dir.path / "study").string();
  writePlan(jobs, spec, out);
  for (const Job& j : jobs)
    writeHandRow(out, j, j.kind == "reference" ? 10 : 5, j.kind == "reference" ? 0 : 0.02 * j.lightScale, "R");
  std::FILE* sink = std::fopen("/dev/null", "w");
  const MergeSummary m = mergeStudy(out, sink);
  std::fclose(sink);
  EXPECT_EQ(m.ok, 6u);
  const fs::path report = fs::path(out) / "report";
  const std::string lightSize = readText(report / "light-size.md");
  EXPECT_NE(lightSize.find("| technique | x0.5 | x1 | x2 |"), std::string::npos) << lightSize;
  EXPECT_NE(lightSize.find("| pcss | 0.0100 | 0.0200 | 0.0400 |"), std::string::npos) << lightSize;
  EXPECT_NE(lightSize.find("visibility RMSE vs same-sample reference. Chart:"), std::string::npos) << lightSize;
  EXPECT_TRUE(fs::exists(report / "light-size-default.svg"));
  const std::string stages = readText(report / "stages.md");
  EXPECT_NE(stages.find("### samples=8 light=2"), std::string::npos) << stages;
  EXPECT_NE(stages.find("| pcss | 5.00 [5.00, 5.00] | 0.50 | 0.0 | work 5.00 [5.00, 5.00] | answer 42 |"),
            std::string::npos)
      << stages;
  const std::string headline = readText(report / "headline.md");
  EXPECT_NE(headline.find("| pcss | samples=8 light=0.5 |"), std::string::npos) << headline;
}

}  // namespace
}  // namespace penumbra::study
