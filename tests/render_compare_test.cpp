// compareTechniques: sweeps render each technique once per preset that changes what
// it renders, a samples sweep brings in the converged reference, and --frames measures flicker
// against the reference's own change (exact for dcs, zero for every technique on a still).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "compare/report.h"
#include "render_test_util.h"
#include "cli/options.h"

using penumbra::cli::parseSweep;

namespace penumbra::test {
namespace {

std::size_t runsOf(const CompareResult& r, const std::string& technique) {
  return std::size_t(
      std::count_if(r.runs.begin(), r.runs.end(), [&](auto& run) { return run.technique == technique; }));
}

TEST(Compare, SweepPresetsAndDeduplication) {
  Scene scene = loadScene(scenePath("scenes/hard/01-cube-on-plane.json"));
  CompareOptions o = compareOptions({"hard-sv", "mvr"});
  o.sweeps = {parseSweep("samples=4,8"), parseSweep("map=64,128")};
  o.timingFrames = 1, o.warmup = 0, o.progress = 0;
  CompareResult r = compareTechniques(context(), scene, settings(48, 4), o);
  ASSERT_EQ(r.presets.size(), 4u);
  EXPECT_EQ(r.presets[1].label, "samples=4 map=128");
  EXPECT_EQ(r.presets[2].samples, 8);
  // hard-sv reads no map: once per sample count; mvr: once per preset; a reference per preset.
  EXPECT_EQ(runsOf(r, "hard-sv"), 2u);
  EXPECT_EQ(runsOf(r, "mvr"), 4u);
  EXPECT_EQ(runsOf(r, "raytrace"), 4u);
  EXPECT_TRUE(r.hasConverged()) << "a samples sweep measures against the converged reference";
  for (auto& run : r.runs) {
    ASSERT_TRUE(run.converged) << run.technique;
    EXPECT_GT(run.total.median, 0.0);
    if (run.technique == "mvr") {
      EXPECT_EQ(run.params.size(), 1u);
      EXPECT_LT(run.errors.visibility.rmse, 0.05) << r.presets[run.preset].label;
    }
  }
  // More samples: the same-sample reference gets closer to the converged one.
  double ref4 = r.runs[0].converged->visibility.rmse, ref8 = -1;
  for (auto& run : r.runs)
    if (run.reference && r.presets[run.preset].samples == 8) ref8 = run.converged->visibility.rmse;
  EXPECT_LT(ref8, ref4);
  EXPECT_EQ(plottedRuns(r).size(), r.runs.size());
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// One technique's failure is its row of the report, not the end of the run. vssm
// refuses a map that is not a power of two when it renders (its min-max hierarchy halves the
// map); dcs and hard-sv, before and after it, go on and measure as they would alone.
class CompareFailure : public TempDirTest {};

TEST_F(CompareFailure, AFailedTechniqueIsItsRowAndTheOthersGoOn) {
  Scene scene = loadScene(scenePath("scenes/hard/01-cube-on-plane.json"));
  CompareOptions o = compareOptions({"dcs", "vssm", "hard-sv"});
  o.params = {"map=1000"};
  o.timingFrames = 1, o.warmup = 0, o.progress = 0;
  o.outDir = dir_.string();
  CompareResult r = compareTechniques(context(), scene, settings(48, 8), o);
  ASSERT_EQ(r.runs.size(), 4u);
  const CompareRun& failed = r.runs[2];
  EXPECT_EQ(failed.technique, "vssm");
  ASSERT_TRUE(failed.failed);
  EXPECT_NE(failed.failure.find("not a power of two"), std::string::npos) << failed.failure;
  EXPECT_TRUE(failed.image.empty());
  for (std::size_t i : {0u, 1u, 3u}) {
    EXPECT_FALSE(r.runs[i].failed) << r.runs[i].technique << ": " << r.runs[i].failure;
    EXPECT_GT(r.runs[i].total.median, 0.0) << r.runs[i].technique;
  }
  EXPECT_EQ(r.runs[1].technique, "dcs");
  EXPECT_LE(r.runs[1].errors.visibility.rmse, 1e-3) << "dcs equals the reference per sample";
  EXPECT_EQ(r.runs[3].technique, "hard-sv");
  EXPECT_GT(r.runs[3].errors.visibility.pixelsCounted, 0);
  for (std::size_t i : plottedRuns(r)) EXPECT_FALSE(r.runs[i].failed) << "a failed run has no point";
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);

  // Every output says so: the table, the JSON, the CSV and the page.
  writeReport(r, dir_.string());
  auto read = [&](const std::string& name) {
    std::ifstream in(dir_ / name);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  std::string table = read("table.txt");
  EXPECT_NE(table.find("vssm                             FAILED: vssm: map size 1000 is not a power of two"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("hard-sv "), std::string::npos);
  nlohmann::json j = nlohmann::json::parse(read("report.json"));
  ASSERT_EQ(j["runs"].size(), 4u);
  EXPECT_EQ(j["runs"][2]["status"], "failed");
  EXPECT_NE(j["runs"][2]["error"].get<std::string>().find("not a power of two"), std::string::npos);
  EXPECT_FALSE(j["runs"][2].contains("errors")) << "no numbers for a run that never rendered";
  EXPECT_EQ(j["runs"][1]["status"], "ok");
  EXPECT_EQ(j["runs"][3]["status"], "ok");
  std::istringstream csv(read("report.csv"));
  std::string header, line;
  std::getline(csv, header);
  EXPECT_NE(header.find(",status,error"), std::string::npos) << header;
  int failedRows = 0, okRows = 0;
  while (std::getline(csv, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), std::count(header.begin(), header.end(), ',')) << line;
    if (line.find(",vssm,") != std::string::npos) {
      EXPECT_NE(line.find(",failed,vssm: map size 1000 is not a power of two"), std::string::npos) << line;
      ++failedRows;
    } else {
      EXPECT_NE(line.find(",ok,"), std::string::npos) << line;
      ++okRows;
    }
  }
  EXPECT_EQ(failedRows, 1);
  EXPECT_EQ(okRows, 3);
  std::string html = read("index.html");
  EXPECT_NE(html.find("<tr class=\"failed\"><td class=\"l\">vssm</td>"), std::string::npos);
  EXPECT_NE(html.find("<b>failed:</b> vssm: map size 1000 is not a power of two"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir_ / "dcs.png"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "hard-sv.png"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "vssm.png"));
}

// The report is rewritten after every row, marked incomplete until the run ends: an interrupted
// run leaves a report that says so (it left the previous run's complete-looking report).
TEST(Compare, TheReportIsMarkedIncompleteUntilTheLastRow) {
  Scene scene = loadScene(scenePath("scenes/hard/01-cube-on-plane.json"));
  CompareOptions o = compareOptions({"none", "hard-sv"});
  o.timingFrames = 1, o.warmup = 0, o.progress = 0;
  std::vector<std::string> marks, tables;
  o.onRow = [&](const CompareResult& partial) {
    marks.push_back(partial.info.value("incomplete", std::string()));
    tables.push_back(reportTable(partial));
    EXPECT_NE(reportHtml(partial).find("<strong>Incomplete</strong>: " + marks.back()), std::string::npos);
  };
  const CompareResult r = compareTechniques(context(), scene, settings(32, 4), o);
  ASSERT_EQ(marks, (std::vector<std::string>{"1 of 3 rows", "2 of 3 rows", "3 of 3 rows"}));
  EXPECT_EQ(tables[0].rfind("INCOMPLETE: 1 of 3 rows", 0), 0u) << tables[0];
  EXPECT_FALSE(r.info.contains("incomplete"));
  EXPECT_EQ(reportTable(r).find("INCOMPLETE"), std::string::npos);
}

// A failed reference leaves nothing to measure against: the comparison ends, naming it.
TEST(Compare, AFailedReferenceEndsTheRun) {
  Scene scene = loadScene(scenePath("scenes/hard/01-cube-on-plane.json"));
  scene.lights[0].intensity = NAN;  // every technique's shaded image is NaN, the reference's first
  CompareOptions o = compareOptions({"hard-sv"});
  o.timingFrames = 1, o.warmup = 0, o.progress = 0;
  try {
    compareTechniques(context(), scene, settings(32, 4), o);
    ADD_FAILURE() << "a comparison without a reference";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("compare: the reference (raytrace) failed: raytrace:"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

// Receivers beyond the shadow maps' max-angle are left unshadowed by design. compare
// counts them per pixel, measures the error without them and writes their mask; with a point
// light inside the cube (hard case 27) they are mvr's whole error (0.51 with them, 0.018
// without at 128 px); dcs leaves none.
TEST(Compare, PixelsOutsideTheShadowMapsAreCountedAndMasked) {
  Scene scene = loadScene(scenePath("scenes/hard/27-point-inside.json"));
  CompareOptions o = compareOptions({"mvr", "dcs"});
  o.timingFrames = 1, o.warmup = 0, o.progress = 0;
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "penumbra_unshadowed";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "insets");
  o.outDir = dir.string();
  o.writeExr = false;
  CompareResult r = compareTechniques(context(), scene, settings(64, 4), o);
  bool sawMvr = false;
  for (auto& run : r.runs) {
    if (run.technique == "mvr") {
      sawMvr = true;
      double outside = -1.0;
      for (auto& [k, v] : run.statistics)
        if (k == "pixels outside maps") outside = v;
      EXPECT_GT(run.errors.unshadowedPixels, 64 * 64 / 20);
      EXPECT_EQ(double(run.errors.unshadowedPixels), outside);
      EXPECT_GT(run.errors.visibility.rmse, 0.3);
      EXPECT_LT(run.errors.visibilityExceptUnshadowed.rmse, 0.05);
      EXPECT_EQ(run.unshadowedMask, "mvr_unshadowed.png");
      EXPECT_TRUE(std::filesystem::exists(dir / run.unshadowedMask));
    } else {
      EXPECT_EQ(run.errors.unshadowedPixels, 0) << run.technique;
      EXPECT_TRUE(run.unshadowedMask.empty()) << run.technique;
    }
  }
  EXPECT_TRUE(sawMvr);
  const nlohmann::json j = r.json();
  EXPECT_EQ(j["runs"][1]["unshadowedMask"], "mvr_unshadowed.png");
  EXPECT_GT(j["runs"][1]["errors"]["unshadowedPixels"].get<std::int64_t>(), 0);
  std::filesystem::remove_all(dir);
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

TEST(Compare, ParametersNoTechniqueReadsAreRefusedBeforeRendering) {
  Scene scene = loadScene(scenePath("scenes/hard/01-cube-on-plane.json"));
  CompareOptions o = compareOptions({"hard-sv"});
  o.sweeps = {parseSweep("map=64,128")};
  o.progress = 0;
  EXPECT_THROW(compareTechniques(context(), scene, settings(32, 4), o), Error);
  o.techniques = findTechniques({"mvr"});
  o.params = {"map=64"};
  EXPECT_THROW(compareTechniques(context(), scene, settings(32, 4), o), Error) << "swept and given";
}

TEST(Compare, FlickerIsZeroOnAStillAndExactForDcs) {
  CompareOptions o = compareOptions({"hard-sv", "dcs", "mvr"});
  o.frames = 3, o.warmup = 0, o.progress = 0;
  Scene still = loadScene(scenePath("scenes/hard/01-cube-on-plane.json"));
  ASSERT_FALSE(still.isAnimated());
  CompareResult r = compareTechniques(context(), still, settings(48, 8), o);
  for (auto& run : r.runs) {
    if (run.reference) continue;
    EXPECT_EQ(run.flicker, 0.0) << run.technique << ": the same frame three times";
    EXPECT_EQ(run.referenceMotion, 0.0);
  }

  Scene fan = loadScene(scenePath("scenes/spinning-fan.json"));
  ASSERT_TRUE(fan.isAnimated());
  o.frames = 4;
  o.fps = 10.0f;  // 3 degrees per frame of the blades
  r = compareTechniques(context(), fan, settings(64, 8), o);
  for (auto& run : r.runs) {
    if (run.reference) continue;
    EXPECT_GT(run.referenceMotion, 0.01) << "the blades' shadows move";
    if (run.technique == "dcs") {
      EXPECT_LT(run.flicker, 1e-4) << "dcs changes exactly as the reference";
    }
    if (run.technique == "mvr") {
      EXPECT_LT(run.flicker, 0.05);
    }
    if (run.technique == "hard-sv") {
      EXPECT_GT(run.flicker, 0.01) << "hard shadows do not move like soft ones";
    }
    EXPECT_GE(run.meanFrameRmse, 0.0);
  }
  EXPECT_TRUE(r.hasTemporal());
  EXPECT_EQ(gl::Context::takeErrorCount(), 0);
}

TEST(Compare, PosedSceneMovesOnlyWhatSpins) {
  Scene fan = loadScene(scenePath("scenes/spinning-fan.json"));
  Scene later = fan.posedAt(3.0f);    // blades 90 degrees on: the cross looks the same
  Scene quarter = fan.posedAt(1.5f);  // 45 degrees
  for (std::size_t m = 0; m < fan.meshes.size(); ++m) {
    const auto& a = fan.meshes[m].mesh.positions;
    const auto& b = quarter.meshes[m].mesh.positions;
    ASSERT_EQ(a.size(), b.size());
    float moved = 0.0f;
    for (std::size_t i = 0; i < a.size(); ++i) moved = std::max(moved, glm::length(a[i] - b[i]));
    if (fan.meshes[m].spin.active()) {
      EXPECT_GT(moved, 0.1f) << fan.meshes[m].name;
    } else {
      EXPECT_EQ(moved, 0.0f) << fan.meshes[m].name;
    }
  }
  // The light turns 6 degrees/s about the vertical through the origin; its height is kept.
  EXPECT_NEAR(later.lights[0].position.y, fan.lights[0].position.y, 1e-5f);
  EXPECT_NEAR(glm::length(glm::vec2(later.lights[0].position.x, later.lights[0].position.z)),
              glm::length(glm::vec2(fan.lights[0].position.x, fan.lights[0].position.z)), 1e-5f);
  EXPECT_GT(glm::length(later.lights[0].position - fan.lights[0].position), 0.02f);
}

}  // namespace
}  // namespace penumbra::test
