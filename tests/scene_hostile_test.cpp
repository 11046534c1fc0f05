// Hostile inputs (a downloaded scene is untrusted): nesting, sizes and memory, values the
// loaders once accepted without a word, properties of the wrong type, and messages that must name
// the right thing. Every file is generated here; expected everywhere: one penumbra::Error line
// naming the file and the problem (before anything large is allocated), or a warning saying
// what was changed or dropped.
#include <gtest/gtest.h>

#include <zlib.h>

#include <cstring>
#include <fstream>

#include "core/error.h"
#include "core/image_io.h"
#include "core/memory.h"
#include "scene/loaders.h"
#include "scene_test_util.h"

namespace penumbra {
namespace {

using detail::Json;
using test::cubeDocument;
using test::expectError;
using test::hasWarning;
using test::sceneWithTexture;

// ---------------------------------------------------------------------------------------------
// Hostile inputs: nesting and size. A value nested 70,000 deep (in a scene file or a --set
// value) crashed the messages that quoted it (a recursive dump), glTF `extras` 20,000 deep
// crashed tinygltf's conversion, and a 1 MB bad string came back as a 1 MB "line".

std::string nested(std::size_t depth) { return std::string(depth, '[') + "1" + std::string(depth, ']'); }

TEST(SceneHostile, DeepNestingIsRefusedBeforeAnythingRecurses) {
  test::TempDir dir;
  const std::string scene = dir.file("deep.json", "{\"name\": \"deep\", \"background\": " + nested(70000) + "}");
  try {
    loadScene(scene);
    ADD_FAILURE() << "no error for a value nested 70,000 deep";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(scene), std::string::npos) << what;
    EXPECT_NE(what.find("nested deeper than 128 arrays and objects"), std::string::npos) << what;
    EXPECT_LT(what.size(), 600u) << "one short line";
  }
  // 128 levels are read (and then refused for what they are, quoting at most 80 characters).
  const std::string ok = dir.file("ok.json", "{\"background\": " + nested(127) + "}");
  try {
    loadScene(ok);
    ADD_FAILURE() << "a nested background is not a colour";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("nested deeper"), std::string::npos) << e.what();
    EXPECT_LT(std::string(e.what()).size(), 400u) << e.what();
  }
  const std::string plain = dir.file("plain.json", "{}");
  expectError([&] { loadScene(plain, {"camera.fov=" + nested(70000)}); }, "override",
              "the value is nested deeper than 128 arrays and objects");

  Json doc = cubeDocument();
  std::string extras;
  for (int i = 0; i < 20000; ++i) extras += "{\"a\":";
  extras += "1" + std::string(20000, '}');
  std::string text = doc.dump();
  text.insert(text.rfind('}'), ",\"extras\":" + extras);
  const std::string gltf = dir.file("deep.gltf", text);
  expectError([&] { loadScene(gltf); }, gltf, "extras.a.a.a");
}

TEST(SceneHostile, BadValuesAreQuotedShort) {
  test::TempDir dir;
  const std::string big(1 << 20, 'x');
  const std::string scene = dir.file("long.json", "{\"resolution\": \"" + big + "\"}");
  try {
    loadScene(scene);
    ADD_FAILURE() << "a string is not a resolution";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("(1048578 characters)"), std::string::npos) << what.substr(0, 300);
    EXPECT_LT(what.size(), 400u);
  }
  // A message built from anything stays one line of at most kMaxErrorMessage characters.
  const Error e("where", std::string(100000, 'y') + "\n");
  EXPECT_LE(std::string(e.what()).size(), kMaxErrorMessage + 40);
  EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  // Abbreviated at a whole UTF-8 sequence ("é" is two bytes).
  std::string accents;
  for (int i = 0; i < 100; ++i) accents += "\xc3\xa9";
  const std::string shown = abbreviate(accents, 81);
  EXPECT_EQ(shown.substr(0, 80), accents.substr(0, 80));
  EXPECT_EQ(shown.substr(80, 3), "...");
}

// Accepted silently before: a glTF light of negative intensity or colour (a scene file's was
// refused), a colour of 4 numbers read as white, two lights of one name (the LUT tool overwrote
// the first one's tables), box/plane/quad sizes of 0, -0 or 1e-45 and collinear quad corners (the
// object vanished), a light texture with negative texels (a visibility layer of -5).
TEST(SceneHostile, WhatWasAcceptedSilentlyIsRefusedOrNamed) {
  test::TempDir dir;
  const auto withLight = [&](const std::string& name, const Json& light, int nodes) {
    Json doc = cubeDocument();
    doc["extensionsUsed"] = Json::array({"KHR_lights_punctual"});
    doc["extensions"]["KHR_lights_punctual"]["lights"] = Json::array({light});
    for (int i = 1; i < nodes; ++i) {
      doc["nodes"].push_back(Json{{"translation", {0.0, 2.0 * i, 0.0}}});
      doc["scenes"][0]["nodes"].push_back(i);
    }
    for (int i = 0; i < nodes; ++i) doc["nodes"][std::size_t(i)]["extensions"]["KHR_lights_punctual"]["light"] = 0;
    return dir.file(name, doc.dump());
  };
  const std::string negative = withLight("negative.gltf", Json{{"type", "point"}, {"intensity", -1.0}}, 1);
  expectError([&] { loadScene(negative); }, negative, "a negative intensity or colour");
  const std::string red = withLight("red.gltf", Json{{"type", "point"}, {"color", {1.0, -0.5, 0.0}}}, 1);
  expectError([&] { loadScene(red); }, red, "a negative intensity or colour");
  const std::string four = withLight("four.gltf", Json{{"type", "point"}, {"color", {1.0, 0.5, 0.0, 1.0}}}, 1);
  expectError([&] { loadScene(four); }, four, "a light's color must be 3 numbers, got [1.0,0.5,0.0,1.0]");
  // One light definition on two nodes: two lights, named apart by their nodes.
  const std::string shared = withLight("shared.gltf", Json{{"type", "point"}, {"name", "lamp"}}, 2);
  std::vector<std::string> lamps;
  for (const Light& l : loadScene(shared).lights)  // (a bare glTF gets a default light too)
    if (l.name.rfind("lamp", 0) == 0) lamps.push_back(l.name);
  ASSERT_EQ(lamps.size(), 2u);
  EXPECT_EQ(lamps[0], "lamp");
  EXPECT_EQ(lamps[1].rfind("lamp@", 0), 0u) << lamps[1];
  const std::string twice = dir.file("twice.json", R"({"objects": [{"shape": "plane"}],
      "lights": [{"name": "key", "type": "point", "position": [0, 2, 0]}, {"name": "key", "type": "point", "position": [1, 2, 0]}]})");
  expectError([&] { loadScene(twice); }, twice,
              "lights[1] 'key': has the name of lights[0] 'key': light names must differ");

  for (const char* size : {"0", "-0", "[1, 0]", "[1, -2]"}) {
    const std::string path =
        dir.file("zero.json", std::string(R"({"objects": [{"shape": "plane", "size": )") + size + "}]}");
    expectError([&] { loadScene(path); }, path, "size: must be positive");
  }
  const std::string tiny = dir.file("tiny.json", R"({"objects": [{"shape": "box", "size": 1e-45}]})");
  expectError([&] { loadScene(tiny); }, tiny, "no triangle of the box has an area in float");
  const std::string line =
      dir.file("line.json", R"({"objects": [{"shape": "quad", "corners": [[0,0,0],[1,0,0],[2,0,0],[3,0,0]]}]})");
  expectError([&] { loadScene(line); }, line, "no triangle of the quad has an area in float");

  // What a glTF holds that penumbra does not use is said, once each.
  Json extra = cubeDocument();
  extra["cameras"] = Json::array({Json{{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}});
  extra["extensionsUsed"] = Json::array({"KHR_materials_pbrSpecularGlossiness", "KHR_materials_clearcoat"});
  extra["materials"] = Json::array({Json{{"pbrMetallicRoughness", {{"baseColorFactor", {2.0, 0.5, 0.5, 1.0}}}},
                                         {"emissiveFactor", {1.0, 1.0, 1.0}},
                                         {"extensions", {{"KHR_materials_pbrSpecularGlossiness", Json::object()}}}}});
  extra["meshes"][0]["primitives"][0]["material"] = 0;
  extra["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 0;  // the positions, read as colours
  const Scene said = loadScene(dir.file("extra.gltf", extra.dump()));
  for (const char* w : {"1 camera(s) not used", "extension KHR_materials_clearcoat is not read",
                        "extension KHR_materials_pbrSpecularGlossiness is not used (shaded as metallic-roughness",
                        "emissiveFactor is not used", "baseColorFactor outside [0, 1], clamped",
                        "1 primitive(s) with COLOR_0: vertex colours are not used"})
    EXPECT_TRUE(hasWarning(said, w)) << w;

  const std::string far = dir.file("far.json", R"({"objects": [{"shape": "box"}],
      "camera": {"position": [0, 0, 5], "target": [0, 0, 0], "near": 1e30}})");
  expectError([&] { loadScene(far); }, far, "camera.near: 1e+30 is beyond every object");

  Image img(2, 2, 3, 0.5f);
  img.at(1, 1, 2) = -5.0f;
  writeExr(dir.file("neg.exr", ""), {{"", &img}});
  const std::string textured = dir.file("neg.json", sceneWithTexture("neg.exr"));
  expectError([&] { loadScene(textured); }, textured, "has 1 negative values (a light cannot emit negative radiance)");
}

// ---------------------------------------------------------------------------------------------
// Memory from small files: sizes are read from headers and glTF instancing is counted before
// anything is decoded or placed, against the run's budget (core/memory.h), naming the file, the
// item and the estimate.

// A PNG of `width` x `height` 1-bit grey texels, all 0 (deflate makes 16384^2 a 32 KiB file), or
// with `idat` as its compressed data when given.
std::string greyPng(std::uint32_t width, std::uint32_t height, const std::string& idat = {}) {
  auto u32 = [](std::uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16 & 0xff), char(v >> 8 & 0xff), char(v & 0xff)};
  };
  auto chunk = [&](const std::string& type, const std::string& data) {
    const std::string body = type + data;
    return u32(std::uint32_t(data.size())) + body +
           u32(std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
  };
  std::string data = idat;
  if (data.empty()) {
    const std::string raw = std::string(std::size_t(height) * (1 + (width + 7) / 8), '\0');
    uLongf size = compressBound(uLong(raw.size()));
    data.resize(size);
    compress2(reinterpret_cast<Bytef*>(data.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
              uLong(raw.size()), 9);
    data.resize(size);
  }
  const std::string header = u32(width) + u32(height) + std::string{1, 0, 0, 0, 0};  // 1-bit grey
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) + chunk("IDAT", data) + chunk("IEND", "");
}

// Sets the run's memory budget for one test and lifts it after.
struct Budget {
  explicit Budget(double bytes) { setMemoryBudget(bytes); }
  ~Budget() { setMemoryBudget(0.0); }
};

TEST(SceneHostile, MemoryIsEstimatedFromHeadersBeforeAllocating) {
  test::TempDir dir;
  // A 58-byte PNG declaring 16000^2: its bytes cannot hold that many rows (deflate's 1032:1).
  dir.file("claims.png", greyPng(16000, 16000, "x"));
  const std::string claims = dir.file("claims.json", sceneWithTexture("claims.png"));
  expectError([&] { loadScene(claims); }, dir.path() + "/claims.png",
              "declares 16000x16000 texels (30 MiB of rows) in 58 bytes, more than deflate can compress into them");

  // A real 16384^2 PNG of 32 KiB: 5 GiB to decode, refused under a 1 GiB budget naming it.
  const std::string big = dir.file("big.png", greyPng(16384, 16384));
  EXPECT_LT(std::ifstream(big, std::ios::binary | std::ios::ate).tellg(), 64 * 1024);
  const std::string scene = dir.file("big.json", sceneWithTexture("big.png"));
  const Budget budget(1024.0 * 1048576.0);
  try {
    loadScene(scene);
    ADD_FAILURE() << "a 16384^2 texture decoded under a 1 GiB budget";
  } catch (const MemoryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(big + ": decoding its 16384x16384 texels needs about 5120 MiB"), std::string::npos) << what;
    EXPECT_NE(what.find("the run's memory budget of 1024 MiB"), std::string::npos) << what;
  }
  // `penumbra info` reads headers only: the same scene loads, its texture's sides known, no pixel.
  const Scene headers = loadScene(scene, {}, LoadOptions{/*decodeTextures=*/false});
  ASSERT_EQ(headers.textures.size(), 1u);
  EXPECT_EQ(headers.textures[0].width, 16384);
  EXPECT_EQ(headers.textures[0].height, 16384);
  EXPECT_TRUE(headers.textures[0].image.empty());

  // glTF instancing: one mesh declaring 10^6 triangles on 100 nodes is 10^8 triangles, refused
  // before one is placed. (Its indices are all 0: the mesh itself would be dropped as degenerate.)
  Json doc = cubeDocument();
  dir.file("many.bin", std::string(96 + 6000000, '\0'));
  doc["buffers"][0] = Json{{"uri", "many.bin"}, {"byteLength", 96 + 6000000}};
  doc["bufferViews"][1]["byteLength"] = 6000000;
  doc["accessors"][1]["count"] = 3000000;
  for (int i = 1; i < 100; ++i) {
    doc["nodes"].push_back(Json{{"mesh", 0}, {"translation", {2.0 * i, 0.0, 0.0}}});
    doc["scenes"][0]["nodes"].push_back(i);
  }
  const std::string many = dir.file("many.gltf", doc.dump());
  expectError([&] { loadScene(many); }, many,
              "placing 100000000 triangles (100 mesh instances on 100 nodes) needs about");

  // A glTF's images, summed from their headers before the first is decoded.
  Json textured = cubeDocument();
  const std::string png = greyPng(8192, 8192);
  textured["images"] = Json::array();
  textured["textures"] = Json::array();
  textured["materials"] = Json::array();
  for (int i = 0; i < 3; ++i) {
    textured["images"].push_back(Json{{"uri", "data:image/png;base64," + test::base64(png)}});
    textured["textures"].push_back(Json{{"source", i}});
    textured["materials"].push_back(Json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", i}}}}}});
  }
  textured["meshes"][0]["primitives"][0]["material"] = 0;
  const std::string images = dir.file("images.gltf", textured.dump());
  expectError([&] { loadScene(images); }, images, "decoding its 3 images (201326592 texels) needs about 4608 MiB");
}

// tinygltf drops a property of the wrong JSON type without a word, or fails without saying
// where: each is refused naming the object and the property.
TEST(SceneHostile, GltfPropertiesOfTheWrongTypeAreNamed) {
  test::TempDir dir;
  const auto refused = [&](const std::string& name, const std::function<void(Json&)>& edit,
                           const std::string& message) {
    Json doc = cubeDocument();
    edit(doc);
    const std::string path = dir.file(name + ".gltf", doc.dump());
    expectError([&] { loadScene(path); }, path, message);
  };
  refused(
      "mesh", [](Json& d) { d["nodes"][0]["mesh"] = "0"; },
      "nodes[0]: 'mesh' must be a non-negative integer, got \"0\"");
  refused(
      "translation",
      [](Json& d) {
        d["nodes"][0]["translation"] = {1.0, 2.0};
      },
      "nodes[0]: 'translation' must be 3 numbers, got [1.0,2.0]");
  refused(
      "children", [](Json& d) { d["nodes"][0]["children"] = "1"; },
      "nodes[0]: 'children' must be an array of non-negative integers");
  refused(
      "mode", [](Json& d) { d["meshes"][0]["primitives"][0]["mode"] = "x"; },
      "meshes[0].primitives[0]: 'mode' must be a non-negative integer, got \"x\"");
  refused(
      "attributes", [](Json& d) { d["meshes"][0]["primitives"][0]["attributes"] = {0}; },
      "meshes[0].primitives[0]: 'attributes' must be an object");
  refused(
      "component", [](Json& d) { d["accessors"][0]["componentType"] = "float"; },
      "accessors[0]: 'componentType' must be a non-negative integer, got \"float\"");
  refused(
      "pbr",
      [](Json& d) {
        d["materials"] = {Json{{"pbrMetallicRoughness", {1, 2}}}};
      },
      "materials[0]: 'pbrMetallicRoughness' must be an object, got [1,2]");
  refused(
      "index",
      [](Json& d) {
        d["materials"] = {Json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", "0"}}}}}}};
      },
      "materials[0]: pbrMetallicRoughness: 'baseColorTexture': 'index' must be a non-negative integer, got \"0\"");
  refused(
      "factor",
      [](Json& d) {
        d["materials"] = {Json{{"emissiveFactor", {1, 1}}}};
      },
      "materials[0]: 'emissiveFactor' must be 3 numbers, got [1,1]");
  // glTF 1.0 is named as such (its objects are dictionaries), not as a missing version.
  refused(
      "v1",
      [](Json& d) {
        d["meshes"] = Json{{"cube", Json::object()}};
        d["asset"].erase("version");
      },
      "a glTF 1.0 file ('meshes' is a dictionary): only glTF 2.0 is read");
  refused(
      "version", [](Json& d) { d["asset"]["version"] = 2; }, "'asset.version' must be a string (\"2.0\"), got 2");
}

// Messages that named the wrong thing, and values that rendered without a word.
TEST(SceneHostile, MessagesNameTheRightThing) {
  test::TempDir dir;
  // UTF-16 (a Windows editor's "Unicode"): said so, not "invalid literal" and a raw byte.
  const std::string text = R"({"objects": [{"shape": "plane"}]})";
  std::string utf16 = "\xff\xfe";
  for (char c : text) utf16 += std::string{c, '\0'};
  const std::string wide = dir.file("wide.json", utf16);
  expectError([&] { loadScene(wide); }, wide, "is UTF-16 or UTF-32 text");
  // A field of view a pixel of which float cannot resolve.
  const std::string narrow = dir.file("narrow.json", R"({"objects": [{"shape": "box"}], "camera": {"fov": 1e-30}})");
  expectError([&] { loadScene(narrow); }, narrow, "camera.fov: 1e-30 degrees: a pixel of the");
  // A file's zero normals shade with the face's normal, and say so.
  const std::string obj = dir.file("normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nvn 0 0 1\nf 1//1 2//2 3//2\n");
  EXPECT_TRUE(hasWarning(loadScene(obj), "1 of its 3 vertex normals are zero or not finite"));
}

}  // namespace
}  // namespace penumbra
