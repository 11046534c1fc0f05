// Technique parameters: every technique reads exactly the parameters it declares,
// dcs takes its options through --param, and the key/value reader words its errors alike for
// --param text and scene JSON. No GL needed (techniques create GL objects in prepare only).
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "core/key_values.h"
#include "pipeline/technique.h"
#include "techniques/registry.h"

namespace penumbra::test {
namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(TechniqueParams, EveryTechniqueReadsExactlyItsDeclarations) {
  for (const TechniqueInfo& t : techniqueTable()) {
    TechniqueParams none;
    auto technique = makeTechnique(t.name, none);
    ASSERT_TRUE(technique) << t.name;
    std::vector<std::string> declared, read = none.known();
    for (auto& p : t.params) declared.push_back(p.key);
    std::sort(declared.begin(), declared.end());
    std::sort(read.begin(), read.end());
    EXPECT_EQ(read, declared) << t.name << ": reads what it does not declare, or declares what it does not read";
    for (auto& p : t.params) {
      EXPECT_FALSE(p.meaning.empty()) << t.name << " " << p.key;
      EXPECT_FALSE(p.defaultText().empty()) << t.name << " " << p.key;
    }
  }
}

TEST(TechniqueParams, OneKeyOneMeaningPerRange) {
  // The same key in two techniques is the same parameter (README's table has a row per key,
  // meaning and values); where a key means something else it says so in its meaning.
  for (auto& a : techniqueTable())
    for (auto& b : techniqueTable())
      for (auto& p : a.params)
        for (auto& q : b.params)
          if (p.key == q.key && p.rangeText() == q.rangeText()) {
            EXPECT_EQ(p.meaning, q.meaning) << a.name << " / " << b.name << ": " << p.key;
          }
}

TEST(TechniqueParams, DcsTakesItsOptionsThroughParam) {
  TechniqueParams p({"coverage=lut", "targets=2", "silhouettes=standard", "opacity=sum", "min-base=64",
                     "gpu-silhouettes=1", "first-bound=3", "profile=0"});
  makeTechnique("dcs", p);
  EXPECT_NO_THROW(p.checkConsumed());
  EXPECT_EQ(p.read().size(), 8u);
  EXPECT_NE(errorOf([] {
              makeTechnique("dcs", TechniqueParams({"coverage=fast"}));
            }).find("param: coverage: expected one of exact, naive, lut, got 'fast'"),
            std::string::npos);
  EXPECT_NE(
      errorOf([] { makeTechnique("dcs", TechniqueParams({"targets=8"})); }).find("param: targets: 8 is outside [1, 7]"),
      std::string::npos);
  EXPECT_NE(errorOf([] {
              makeTechnique("dcs", TechniqueParams({"min-base=48"}));
            }).find("min-base: expected one of 8, 16, 32, 64"),
            std::string::npos);
  // The variants are presets of the same declarations: their defaults differ, their keys do not.
  EXPECT_EQ(findTechnique("dcs-lut").params.size(), findTechnique("dcs").params.size());
  auto coverageOf = [](const std::string& name) {
    for (auto& s : findTechnique(name).params)
      if (s.key == "coverage") return s.defaultText();
    return std::string();
  };
  EXPECT_EQ(coverageOf("dcs"), "exact");
  EXPECT_EQ(coverageOf("dcs-naive"), "naive");
  EXPECT_EQ(coverageOf("dcs-lut"), "lut");
}

TEST(TechniqueParams, UnreadKeysAreRefused) {
  TechniqueParams p({"map=64", "blur=0"});
  makeTechnique("pcss", p);  // pcss (no mask, no min filter) has no blur
  EXPECT_NE(errorOf([&] { p.checkConsumed(); }).find("no technique of this run has a parameter 'blur'"),
            std::string::npos);
}

TEST(KeyValueReader, TextAndJsonValuesShareTheirChecksAndWording) {
  const KeyPlace param{"param", "map", ExitCode::Usage}, scene{"a.json", "camera.resolution", ExitCode::Error};
  KeyValue json;
  json.kind = KeyValue::Kind::Number, json.number = 2.5, json.shown = "2.5";
  EXPECT_EQ(errorOf([&] { readInteger(KeyValue::ofText("2.5"), param, 0, 10); }),
            "param: map: expected an integer, got '2.5'");
  EXPECT_EQ(errorOf([&] { readInteger(json, scene, 0, 10); }),
            "a.json: camera.resolution: expected an integer, got 2.5");
  EXPECT_EQ(errorOf([&] { readNumber(KeyValue::ofText("20"), param, 0, 10); }), "param: map: 20 is outside [0, 10]");
  EXPECT_EQ(errorOf([&] { readNumber(KeyValue::ofText("1e400"), param, 0, 10); }),
            "param: map: not a finite number: '1e400'");
  EXPECT_EQ(errorOf([&] { readNumber(KeyValue::ofText("12abc"), param, 0, 100); }),
            "param: map: expected a number, got '12abc'");
  EXPECT_EQ(readNumber(KeyValue::ofText("0.25"), param, 0, 1), 0.25);
  EXPECT_TRUE(readBoolean(KeyValue::ofText("on"), param));
  EXPECT_FALSE(readBoolean(KeyValue::ofText("0"), param));
  KeyValue yes;
  yes.kind = KeyValue::Kind::String, yes.text = "yes", yes.shown = "\"yes\"";
  EXPECT_EQ(errorOf([&] { readBoolean(yes, scene); }),
            "a.json: camera.resolution: expected true or false, got \"yes\"");
  EXPECT_EQ(readChoice(KeyValue::ofText("lut"), param, {"exact", "naive", "lut"}), 2);
  KeyValue five;
  five.kind = KeyValue::Kind::Integer, five.number = 5, five.shown = "5";
  EXPECT_EQ(readChoice(five, scene, {"1", "5", "9"}), 1);
}

}  // namespace
}  // namespace penumbra::test
