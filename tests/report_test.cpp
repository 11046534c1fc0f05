// The comparison report without GL: the Pareto front, sweep and inset parsing, inset
// choice, and what report.csv / plot.svg / index.html contain for a hand-made result.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/error.h"
#include "compare/frame_file.h"
#include "compare/output.h"
#include "compare/report.h"
#include "cli/options.h"

using penumbra::cli::parseInset;
using penumbra::cli::parseSweep;

namespace penumbra {
namespace {

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + what.size())) ++n;
  return n;
}

TEST(Report, ParetoFrontKeepsOnlyUndominatedPoints) {
  // (time, error): 1 and 3 dominate 2 (slower and worse than 1) and 4 (slower than 3, equal error).
  std::vector<std::pair<double, double>> pts = {{10, 0.5}, {5, 0.2}, {7, 0.3}, {20, 0.01}, {25, 0.01}, {30, 0.001}};
  auto front = paretoFront(pts);
  EXPECT_EQ(front, (std::vector<std::size_t>{1, 3, 5}));
  EXPECT_TRUE(paretoFront({}).empty());
  EXPECT_EQ(paretoFront({{1, 1}}), (std::vector<std::size_t>{0}));
  // Equal times: only the more accurate one.
  EXPECT_EQ(paretoFront({{2, 0.5}, {2, 0.1}}), (std::vector<std::size_t>{1}));
  // Equal errors up to rounding: the faster one only.
  EXPECT_EQ(paretoFront({{2, 0.0376}, {9, 0.0376 * (1 - 1e-7)}}), (std::vector<std::size_t>{0}));
}

TEST(Report, SweepAndInsetParsing) {
  SweepAxis a = parseSweep("samples=16,32,64");
  EXPECT_EQ(a.key, "samples");
  EXPECT_EQ(a.values, (std::vector<std::string>{"16", "32", "64"}));
  EXPECT_EQ(parseSweep("map=512").values.size(), 1u);
  for (const char* bad : {"samples", "=1,2", "samples=", "samples=1,,2", "samples=4,4"})
    EXPECT_THROW(parseSweep(bad), Error) << bad;
  Inset r = parseInset("0,8,16,24");
  EXPECT_EQ(r.x, 0);
  EXPECT_EQ(r.y, 8);
  EXPECT_EQ(r.w, 16);
  EXPECT_EQ(r.h, 24);
  for (const char* bad : {"1,2,3", "1,2,3,4,5", "-1,0,4,4", "0,0,0,4", "a,0,4,4"})
    EXPECT_THROW(parseInset(bad), Error) << bad;
}

TEST(Report, InsetsGoWhereThePenumbraIs) {
  FrameResult ref;
  const int W = 100, H = 80;
  ref.color = Image(W, H, 3);
  ref.gbuffer.valid.assign(std::size_t(W) * H, 1);
  LightResult l;
  l.visibility = Image(W, H, 3, 1.0f);
  // A penumbra block at (60..79, 10..29) and a smaller one at (5..14, 50..59).
  for (int y = 10; y < 30; ++y)
    for (int x = 60; x < 80; ++x)
      for (int c = 0; c < 3; ++c) l.visibility.at(x, y, c) = 0.5f;
  for (int y = 50; y < 60; ++y)
    for (int x = 5; x < 15; ++x)
      for (int c = 0; c < 3; ++c) l.visibility.at(x, y, c) = 0.3f;
  ref.lights.push_back(l);
  auto insets = chooseInsets(ref, 2);
  ASSERT_EQ(insets.size(), 2u);
  EXPECT_EQ(insets[0].w, 16);  // min(W, H) / 5
  EXPECT_TRUE(insets[0].x >= 56 && insets[0].x + insets[0].w <= 84 && insets[0].y >= 6 &&
              insets[0].y + insets[0].h <= 34)
      << insets[0].x << "," << insets[0].y;
  EXPECT_TRUE(insets[1].x <= 14 && insets[1].x + insets[1].w >= 5 && insets[1].y <= 59 &&
              insets[1].y + insets[1].h >= 50)
      << insets[1].x << "," << insets[1].y;
  // No penumbra at all: no inset.
  for (auto& v : ref.lights[0].visibility.data) v = 1.0f;
  EXPECT_TRUE(chooseInsets(ref, 2).empty());
}

CompareResult handMade() {
  CompareResult r;
  r.info = {{"sceneName", "s<&>"}, {"scene", "x.json"}, {"width", 8}, {"height", 8}, {"samples", 4}};
  ComparePreset p0, p1;
  p0.width = p0.height = p1.width = p1.height = 8;
  p0.samples = 4, p1.samples = 8;
  p0.label = "samples=4", p1.label = "samples=8";
  p0.values = {{"samples", "4"}}, p1.values = {{"samples", "8"}};
  r.presets = {p0, p1};
  auto run = [](const std::string& name, std::size_t preset, bool ref, double ms, double err, double conv) {
    CompareRun c;
    c.technique = name, c.preset = preset, c.reference = ref;
    c.total = {ms, ms * 0.9, ms * 1.2};
    c.stages = {{"a", {ms / 2, ms / 2, ms / 2}}, {"b, c", {ms / 2, ms / 2, ms / 2}}};
    c.errors.visibility.rmse = err;
    TechniqueErrors e;
    e.visibility.rmse = conv;
    c.converged = e;
    c.image = name + ".png";
    return c;
  };
  r.runs = {run("raytrace", 0, true, 5, 0, 0.05),   run("fast", 0, false, 1, 0.2, 0.21),
            run("slow", 0, false, 50, 1e-9, 0.049), run("raytrace", 1, true, 9, 0, 0.03),
            run("fast", 1, false, 1.5, 0.1, 0.12),  run("slow", 1, false, 90, 1e-9, 0.029)};
  return r;
}

// CSV columns of a line, counting commas outside quotes.
std::size_t columns(const std::string& l) {
  std::size_t n = 1;
  bool quoted = false;
  for (char c : l) {
    if (c == '"') quoted = !quoted;
    n += !quoted && c == ',';
  }
  return n;
}

TEST(Report, CsvHasOneRowPerRunAndFixedColumns) {
  CompareResult r = handMade();
  std::istringstream csv(reportCsv(r));
  std::string line;
  std::getline(csv, line);
  const std::size_t header = columns(line);
  EXPECT_GT(header, 25u);
  int rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    EXPECT_EQ(columns(line), header) << line;
  }
  EXPECT_EQ(rows, 6);
  EXPECT_NE(reportCsv(r).find("\"a=0.500;b, c=0.500\""), std::string::npos) << "a field with a comma is quoted";
}

TEST(Report, PlotAndPageShowEveryRun) {
  CompareResult r = handMade();
  ASSERT_TRUE(r.hasConverged());
  EXPECT_EQ(plottedRuns(r).size(), 6u);  // references have an error against the converged one
  std::string svg = speedErrorSvg(r);
  EXPECT_EQ(count(svg, "class=\"point\""), 6u);
  EXPECT_EQ(count(svg, "class=\"pareto\""), 1u);
  EXPECT_NE(svg.find("vs converged reference"), std::string::npos);
  EXPECT_EQ(svg.find("s<&>"), std::string::npos) << "names are escaped";
  std::string html = reportHtml(r);
  EXPECT_EQ(count(html, "<img src=\"fast.png\""), 2u);  // one gallery per preset
  EXPECT_EQ(count(html, "<tr class="), 6u);
  EXPECT_NE(html.find("<svg"), std::string::npos);
  for (const char* remote : {"src=\"http", "href=\"http", "src=\"//", "url("})
    EXPECT_EQ(html.find(remote), std::string::npos) << "nothing loaded from the network: " << remote;
  std::string table = reportTable(r);
  EXPECT_EQ(count(table, "\n"), 7u);
  EXPECT_NE(table.find("conv vis"), std::string::npos);
  EXPECT_NE(table.find("conv img"), std::string::npos) << "the shaded error against the converged reference";
}

// Points carry their technique and family, each has a <text> label with the
// technique's name (the Pareto front's and each family's best shown, the rest hidden until
// hovered), families differ in colour, and the shaded and FLIP axes plot their own errors.
TEST(Report, PlotLabelsFamiliesAndAxes) {
  CompareResult r = handMade();
  for (auto& run : r.runs) {
    run.family = run.technique == "fast" ? TechniqueFamily::SingleMap : TechniqueFamily::ExactPerSample;
    run.flip = run.converged->visibility.rmse * 2;
    run.converged->shaded.rmse = run.converged->visibility.rmse / 2;
  }
  const std::string svg = speedErrorSvg(r);
  EXPECT_EQ(count(svg, "class=\"point\" data-technique=\""), 6u);
  EXPECT_EQ(count(svg, "data-family=\"single map\""), 2u * 3u);  // the group, the point, the label
  EXPECT_EQ(count(svg, "<text class=\"label"), 6u);
  EXPECT_NE(svg.find("data-technique=\"fast\" data-family=\"single map\" x="), std::string::npos);
  EXPECT_NE(svg.find(">fast<tspan fill=\"#555\"> N=4</tspan></text>"), std::string::npos) << "the label holds the name";
  // Five of the six are on the front (all but slow @ 4), each family's best among them: shown
  // where there is room, at least three of them here.
  EXPECT_GE(count(svg, "<text class=\"label\""), 3u);
  EXPECT_NE(svg.find("fill=\"#E69F00\""), std::string::npos);  // single map: orange
  EXPECT_NE(svg.find("fill=\"#0072B2\""), std::string::npos);  // exact: blue
  EXPECT_NE(svg.find(">exact per sample</text>"), std::string::npos) << "the legend groups by family";
  EXPECT_NE(speedErrorSvg(r, ErrorAxis::Flip).find("mean HDR-FLIP vs converged reference"), std::string::npos);
  EXPECT_NE(speedErrorSvg(r, ErrorAxis::Shaded).find("shaded-image RMSE"), std::string::npos);
  EXPECT_NE(speedErrorSvg(r, ErrorAxis::Flip).find("mean HDR-FLIP vs converged reference 0.42"), std::string::npos)
      << "fast @ 4: flip 2 x 0.21";
  const std::string html = reportHtml(r);
  EXPECT_EQ(count(html, "<div class=\"plot\""), 3u);
  EXPECT_EQ(count(html, "<div class=\"plot\" data-axis=\"visibility\">"), 1u) << "the visibility plot shown first";
  EXPECT_NE(html.find("<th>FLIP (mean)</th>"), std::string::npos);

  const auto summary = whichTechniqueWhen(r);
  ASSERT_GE(summary.size(), 3u);
  EXPECT_EQ(summary[0].rfind("Fastest at each error level", 0), 0u) << summary[0];
  EXPECT_NE(summary[0].find("fast @ samples=4 (1.0 ms, 0.2100)"), std::string::npos) << summary[0];
  EXPECT_NE(summary[0].find("slow @ samples=8 (90.0 ms, 0.0290)"), std::string::npos) << summary[0];
  EXPECT_EQ(summary[1].rfind("exact per sample: most accurate slow @ samples=8", 0), 0u) << summary[1];
  EXPECT_EQ(
      summary[2].rfind("single map: most accurate fast @ samples=8 (1.5 ms, 0.1200), fastest fast @ samples=4", 0), 0u)
      << summary[2];
  EXPECT_EQ(summary.back(), "No technique failed or left a pixel unshadowed.");
  CompareRun broken;
  broken.technique = "broken", broken.failed = true, broken.failure = "it broke";
  r.runs.push_back(broken);
  EXPECT_EQ(whichTechniqueWhen(r).back(), "broken @ samples=4 failed: it broke");
}

// Every label the plot must show (front, each family's best) is shown even where the eight
// places beside its point are taken: a cluster of points, one per family and on the front,
// within a few pixels (the default scene's single-map corner, CI stop 28: 4 of 6 shown). The
// labels go out on leader lines; none overlaps another or a point, and all stay in the plot.
TEST(Report, WantedLabelsFindRoomInACluster) {
  CompareResult r = handMade();
  r.runs.clear();
  const TechniqueFamily families[] = {TechniqueFamily::ExactPerSample, TechniqueFamily::MultiView,
                                      TechniqueFamily::SingleMap, TechniqueFamily::Denoised, TechniqueFamily::Hard};
  for (int i = 0; i < 12; ++i) {
    CompareRun c;
    c.technique = "technique-with-a-long-name-" + std::to_string(i), c.preset = 0;
    c.family = families[i % 5];
    const double ms = 10 * (1 + 0.01 * i);  // a front: each a little slower and more accurate
    c.total = {ms, ms, ms};
    c.errors.visibility.rmse = 0.1 * (1 - 0.01 * i);
    r.runs.push_back(c);
  }
  r.runs.push_back(r.runs[0]);
  r.runs.back().technique = "far-away", r.runs.back().total = {1000, 1000, 1000},
  r.runs.back().errors.visibility.rmse = 1e-3;
  const std::string svg = speedErrorSvg(r);
  const std::size_t wanted = count(svg, "data-wanted=\"1\"");
  EXPECT_GE(wanted, 12u) << "the twelve on the front and the far point";
  EXPECT_EQ(count(svg, "<text class=\"label hidden\" data-wanted"), 0u) << svg;
  EXPECT_GE(count(svg, "<line class=\"leader\""), 1u) << "the cluster needs leader lines";
}

// A failed run is a row in every output (the reason, no numbers, no point), with
// the CSV's columns unchanged; the other runs are as before.
TEST(Report, AFailedRunIsARowEverywhere) {
  CompareResult r = handMade();
  CompareRun failed;
  failed.technique = "broken", failed.preset = 1, failed.shading = "modulate";
  failed.params = {"map=1000"};
  failed.failed = true;
  failed.failure = "broken: map size 1000 <is> not a power of two";
  r.runs.push_back(failed);

  EXPECT_EQ(plottedRuns(r).size(), 6u) << "a failed run has no point";
  EXPECT_EQ(count(speedErrorSvg(r), "class=\"point\""), 6u);

  std::string table = reportTable(r);
  EXPECT_EQ(count(table, "\n"), 8u);
  EXPECT_NE(table.find("broken @ samples=8               FAILED: broken: map size 1000 <is> not a power of two\n"),
            std::string::npos)
      << table;

  std::string csv = reportCsv(r);
  std::istringstream lines(csv);
  std::string header, line, last;
  std::getline(lines, header);
  EXPECT_EQ(header.substr(header.size() - 18), "image,status,error") << header;
  int ok = 0;
  while (std::getline(lines, line)) {
    EXPECT_EQ(columns(line), columns(header)) << line;
    ok += line.find(",ok,") != std::string::npos;
    last = line;
  }
  EXPECT_EQ(ok, 6);
  // 23 measured columns, then the 9 of the harness and the pipeline statistics: all empty.
  EXPECT_EQ(last,
            "s<&>,broken,0,samples=8,map=1000,8,8,8,modulate,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,failed,"
            "broken: map size 1000 <is> not a power of two");

  nlohmann::json j = r.json();
  ASSERT_EQ(j["runs"].size(), 7u);
  EXPECT_EQ(j["runs"][6]["status"], "failed");
  EXPECT_EQ(j["runs"][6]["error"], failed.failure);
  for (const char* k : {"totalMs", "errors", "statistics", "stagesMs"}) EXPECT_FALSE(j["runs"][6].contains(k)) << k;
  EXPECT_EQ(j["runs"][1]["status"], "ok");
  EXPECT_TRUE(j["runs"][1].contains("errors"));

  std::string html = reportHtml(r);
  EXPECT_EQ(count(html, "<tr class=\"failed\">"), 1u);
  EXPECT_NE(html.find("<b>failed:</b> broken: map size 1000 &lt;is&gt; not a power of two</td></tr>"),
            std::string::npos);
  EXPECT_EQ(html.find("<is>"), std::string::npos) << "the reason is escaped";
  EXPECT_EQ(count(html, "<img src=\"broken"), 0u) << "no image for a failed run";
}

// The light-size study's chart: a line and a marker per point for each series, the floor for
// exact errors, the legend by family, names escaped.
TEST(Report, LineChartHasALinePerSeries) {
  std::vector<ChartSeries> series = {
      {"dcs", TechniqueFamily::ExactPerSample, {{0.1, 0.0}, {1.0, 0.0}}},
      {"s<&>", TechniqueFamily::SingleMap, {{0.1, 0.01}, {0.5, 0.05}, {1.0, 0.2}}},
  };
  const std::string svg = lineChartSvg("Error against light size", "light width", "RMSE", series);
  EXPECT_EQ(count(svg, "<g class=\"series\""), 2u);
  EXPECT_EQ(count(svg, "<title>"), 5u);
  EXPECT_EQ(svg.find("s<&>"), std::string::npos) << "names are escaped";
  EXPECT_NE(svg.find(">exact per sample</text>"), std::string::npos);
  EXPECT_NE(svg.find(">single map</text>"), std::string::npos);
  EXPECT_NE(svg.find("fill=\"#E69F00\""), std::string::npos);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// A study merges its jobs' rows back into a comparison (study/merge.h): a run read back from
// report.json's JSON writes the same JSON, failed runs, converged errors, noise and FLIP included.
TEST(Report, RunsReadBackFromTheirJson) {
  CompareResult r = handMade();
  r.runs[1].statistics = {{"maps", 4}};
  r.runs[1].memoryBytes = 12345;
  r.runs[1].flip = 0.25;
  r.runs[1].errors.sampleAgreement = 0.9, r.runs[1].errors.sampleMismatches = 7;
  r.runs[1].errors.visibility.rmse = std::nan("");  // written as null, read back as NaN
  r.runs[0].referenceNoise = ReferenceNoise{0.001, 0.002};
  r.runs[0].referenceStatistics = {{"spp", 1024}};
  CompareRun failed;
  failed.technique = "slow", failed.preset = 0, failed.failed = true, failed.failure = "out of memory";
  r.runs[2] = failed;
  const nlohmann::json written = r.json();
  CompareResult back = r;
  for (std::size_t i = 0; i < r.runs.size(); ++i)
    back.runs[i] = runFromJson(written["runs"][i], r.runs[i].preset, "report.json");
  const nlohmann::json reread = back.json();
  for (std::size_t i = 0; i < r.runs.size(); ++i) EXPECT_EQ(reread["runs"][i].dump(), written["runs"][i].dump()) << i;
  EXPECT_TRUE(std::isnan(back.runs[1].errors.visibility.rmse));
  nlohmann::json bad = written["runs"][1];
  bad.erase("errors");
  EXPECT_THROW(runFromJson(bad, 0, "row.json"), Error);
  bad = written["runs"][1];
  bad["family"] = "psychic";
  EXPECT_THROW(runFromJson(bad, 0, "row.json"), Error);
}

// Per-sample agreement by the sample's ring on a rect light (LightResult::sampleRadius): two
// pixels, four samples at radii 0.1, 0.3, 0.6 and 0.9 of the half-sides; the technique differs
// from the reference at the third sample in both pixels and at the fourth in one.
TEST(Report, SampleAgreementByRingOfTheLight) {
  FrameResult ref, f;
  ref.gbuffer.width = 2, ref.gbuffer.height = 1, ref.gbuffer.valid = {1, 1};
  ref.color = Image(2, 1, 3, 1.0f);
  LightResult l;
  l.visibility = Image(2, 1, 3, 1.0f);
  l.samples = 4;
  l.perSample.assign(8, 1.0f);
  ref.lights = {l};
  f = ref;
  f.lights[0].sampleRadius = {0.1f, 0.3f, 0.6f, 0.9f};
  f.lights[0].perSample = {1, 1, 0, 0, 1, 1, 0, 1};  // [pixel * 4 + k]
  const TechniqueErrors e = measureErrors(f, ref);
  EXPECT_DOUBLE_EQ(e.sampleAgreement, 5.0 / 8.0);
  EXPECT_EQ(e.sampleAgreementByRing, (std::array<double, 4>{1.0, 1.0, 0.0, 0.5}));
  const nlohmann::json j = errorsJson(e);
  EXPECT_EQ(j.at("sampleAgreementByRing").dump(), "[1.0,1.0,0.0,0.5]");
  // Without radii (another light shape, interleaved sets) there are no rings.
  f.lights[0].sampleRadius.clear();
  EXPECT_FALSE(errorsJson(measureErrors(f, ref)).contains("sampleAgreementByRing"));
}

// A reference's frame kept for other processes (compare/frame_file.h) reads back bit for bit;
// a file cut short, padded or of another kind is an error naming it.
TEST(Report, FramesReadBackBitForBit) {
  FrameResult f;
  f.color = Image(3, 2, 3, 0.25f);
  f.color.data[4] = -0.0f;
  f.colorVariance = Image(3, 2, 3, 1e-9f);
  LightResult l;
  l.visibility = Image(3, 2, 3, 0.5f);
  l.perSample = {0, 1, 0.5f, 0.125f, 1, 1, 0, 0, 1, 0.25f, 0.75f, 1};  // [pixel * 2 + k]
  l.samples = 2;
  l.unshadowed = {0, 1, 0, 0, 1, 0};
  f.lights = {l, l};
  f.lights[1].visibilityVariance = Image(3, 2, 3, 0.01f);
  f.gbuffer.width = 3, f.gbuffer.height = 2;
  f.gbuffer.position.assign(6, glm::vec3(1, 2, 3));
  f.gbuffer.normal.assign(6, glm::vec3(0, 1, 0));
  f.gbuffer.valid = {1, 1, 0, 1, 1, 1};
  f.gbuffer.camera = glm::vec3(0, 0, 5);
  f.gbuffer.origin = glm::dvec3(1e9, 0, -1e9);
  f.memoryBytes = 4096;
  f.statistics = {{"maps", 16}, {"edges", 1e6}};
  const std::string dir = ::testing::TempDir(), path = dir + "/frame.bin";
  writeFrameFile(path, f);
  const FrameResult g = readFrameFile(path);
  EXPECT_EQ(g.color.data, f.color.data);
  EXPECT_EQ(g.colorVariance.data, f.colorVariance.data);
  ASSERT_EQ(g.lights.size(), 2u);
  EXPECT_EQ(g.lights[1].visibility.data, l.visibility.data);
  EXPECT_EQ(g.lights[0].perSample, l.perSample);
  EXPECT_EQ(g.lights[0].samples, 2);
  EXPECT_EQ(g.lights[0].unshadowed, l.unshadowed);
  EXPECT_EQ(g.lights[1].visibilityVariance.data, f.lights[1].visibilityVariance.data);
  EXPECT_EQ(g.gbuffer.position, f.gbuffer.position);
  EXPECT_EQ(g.gbuffer.valid, f.gbuffer.valid);
  EXPECT_TRUE(g.gbuffer.shadingNormal.empty());
  EXPECT_EQ(g.gbuffer.camera, f.gbuffer.camera);
  EXPECT_EQ(g.gbuffer.origin, f.gbuffer.origin);
  EXPECT_EQ(g.memoryBytes, 4096u);
  EXPECT_EQ(g.statistics, f.statistics);
  // The same errors against the frame read back as against the frame in memory.
  EXPECT_EQ(errorsJson(measureErrors(f, g)).dump(), errorsJson(measureErrors(f, f)).dump());

  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto rewrite = [&](const std::string& content) {
    std::ofstream(path, std::ios::binary) << content;
    try {
      readFrameFile(path);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  for (std::size_t cut : {std::size_t(0), std::size_t(5), std::size_t(40), bytes.size() / 2, bytes.size() - 1})
    EXPECT_NE(rewrite(bytes.substr(0, cut)).find("frame.bin"), std::string::npos) << cut;
  EXPECT_NE(rewrite(bytes + "x").find("after its end"), std::string::npos);
  std::string huge = bytes;
  huge[sizeof(std::int32_t) * 3 + 8 + 4] = '\x7f';  // the colour's float count: far past the file
  EXPECT_NE(rewrite(huge).find("cut short"), std::string::npos);
  EXPECT_NE(rewrite("PNMBFRM0" + bytes.substr(8)).find("not a penumbra frame file"), std::string::npos);
}

}  // namespace
}  // namespace penumbra
