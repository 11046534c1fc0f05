// EXR/PNG files: round trips, every reader failure as a one-line penumbra::Error naming the file.
#include <gtest/gtest.h>

#include "test_util.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepScanLineOutputFile.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>

#include "core/error.h"
#include "core/image_io.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using test::expectError;

std::vector<char> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

void truncateTo(const std::string& path, std::size_t size) {
  std::vector<char> bytes = readBytes(path);
  ASSERT_LT(size, bytes.size());
  bytes.resize(size);
  writeBytes(path, bytes);
}

// Runs fn and checks it throws a one-line penumbra::Error about `path` mentioning `needle`.

// A deterministic pattern with values PNG and EXR both have to carry exactly.
Image pattern(int w, int h, int c, float offset = 0.0f) {
  Image img(w, h, c);
  for (std::size_t i = 0; i < img.data.size(); ++i) {
    img.data[i] = offset + float((i * 37) % 101) / 100.0f;
  }
  return img;
}

bool bitEqual(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels &&
         std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

using ImageIoTest = test::TempDirTest;

// ---------------------------------------------------------------------------------------------
// EXR

TEST_F(ImageIoTest, ExrMultiLayerRoundTripIsBitExact) {
  Image rgba = pattern(7, 5, 4);
  rgba.data[0] = -3.5f;
  rgba.data[1] = 1e-40f;  // denormal
  rgba.data[2] = 65504.5f;
  const Image rgb = pattern(7, 5, 3, 0.25f);
  const Image grey = pattern(7, 5, 1, 2.0f);
  const std::string path = file("layers.exr");
  writeExr(path, {{"", &rgba}, {"albedo", &rgb}, {"vis", &grey}});

  EXPECT_TRUE(bitEqual(readExrLayer(path, ""), rgba));
  EXPECT_TRUE(bitEqual(readExrLayer(path, "albedo"), rgb));
  EXPECT_TRUE(bitEqual(readExrLayer(path, "vis"), grey));
  EXPECT_TRUE(bitEqual(readExr(path), rgba));  // plain R,G,B,A come first

  Imf::InputFile in(path.c_str());
  EXPECT_EQ(in.header().compression(), Imf::ZIP_COMPRESSION);
  std::vector<std::string> names;
  for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) {
    EXPECT_EQ(it.channel().type, Imf::FLOAT) << it.name();
    names.push_back(it.name());
  }
  EXPECT_EQ(names, (std::vector<std::string>{"A", "B", "G", "R", "albedo.B", "albedo.G", "albedo.R", "vis.Y"}));
  expectError([&] { readExrLayer(path, "nope"); }, path, "nope");
}

TEST_F(ImageIoTest, ExrReadFillsAlphaAndFindsPrefixedLayer) {
  const Image rgb = pattern(3, 2, 3);
  const std::string path = file("beauty.exr");
  writeExr(path, {{"beauty", &rgb}});
  const Image img = readExr(path);
  ASSERT_EQ(img.channels, 4);
  ASSERT_EQ(img.width, 3);
  ASSERT_EQ(img.height, 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(x, y, c), rgb.at(x, y, c));
      EXPECT_EQ(img.at(x, y, 3), 1.0f);
    }
  }
}

TEST_F(ImageIoTest, ExrYOnlyReadsAsGrey) {
  const Image grey = pattern(4, 3, 1);
  const std::string path = file("grey.exr");
  writeExr(path, {{"", &grey}});
  const Image img = readExr(path);
  ASSERT_EQ(img.channels, 4);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(x, y, c), grey.at(x, y, 0));
      EXPECT_EQ(img.at(x, y, 3), 1.0f);
    }
  }
}

TEST_F(ImageIoTest, ExrDataWindowOffsetIsIgnored) {
  const std::string path = file("offset.exr");
  Imf::Header header(Imath::Box2i({0, 0}, {63, 63}), Imath::Box2i({10, 20}, {13, 22}));
  header.channels().insert("R", Imf::Channel(Imf::FLOAT));
  header.channels().insert("G", Imf::Channel(Imf::FLOAT));
  header.channels().insert("B", Imf::Channel(Imf::FLOAT));
  const Image src = pattern(4, 3, 3);
  Imf::FrameBuffer fb;
  const char* names[] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, src.data.data() + c, header.dataWindow(), 12, 48));
  }
  {
    Imf::OutputFile out(path.c_str(), header);
    out.setFrameBuffer(fb);
    out.writePixels(3);
  }
  const Image img = readExrLayer(path, "");
  EXPECT_TRUE(bitEqual(img, src));
}

TEST_F(ImageIoTest, ExrNonFiniteTexelsAreSanitizedAndCounted) {
  Image img = pattern(5, 4, 3);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  img.at(1, 0, 0) = nan;
  img.at(1, 0, 2) = inf;  // same texel as the NaN: counted once
  img.at(4, 3, 1) = -inf;
  img.at(0, 2, 2) = nan;
  const std::string path = file("nan.exr");
  writeExr(path, {{"", &img}});
  int sanitized = -1;
  const Image back = readExr(path, &sanitized);
  EXPECT_EQ(sanitized, 3);
  EXPECT_EQ(back.at(1, 0, 0), 0.0f);
  EXPECT_EQ(back.at(1, 0, 1), img.at(1, 0, 1));
  EXPECT_EQ(back.at(1, 0, 2), 0.0f);
  EXPECT_EQ(back.at(4, 3, 1), 0.0f);
  EXPECT_EQ(back.at(0, 2, 2), 0.0f);
  for (float v : back.data) EXPECT_TRUE(std::isfinite(v));
  readExrLayer(path, "", &sanitized);
  EXPECT_EQ(sanitized, 3);
}

TEST_F(ImageIoTest, ExrTruncatedFilesAreRejected) {
  const Image img = pattern(64, 64, 3);
  const std::string path = file("t.exr");
  writeExr(path, {{"", &img}});
  const std::size_t size = readBytes(path).size();
  for (std::size_t keep : {size - 1, size / 2, std::size_t(40), std::size_t(6)}) {
    writeExr(path, {{"", &img}});
    truncateTo(path, keep);
    expectError([&] { readExr(path); }, path);
  }
}

TEST_F(ImageIoTest, EmptyMissingAndForeignFilesAreRejected) {
  for (const std::string name : {"empty.exr", "empty.png"}) {
    writeBytes(file(name), {});
    expectError([&] { readTexture(file(name)); }, file(name));
  }
  const std::string text = "this is not an image\n";
  for (const std::string name : {"text.exr", "text.png"}) {
    writeBytes(file(name), std::vector<char>(text.begin(), text.end()));
    expectError([&] { readTexture(file(name)); }, file(name));
  }
  expectError([&] { readExr(file("missing.exr")); }, file("missing.exr"), "cannot open");
  expectError([&] { readPng(file("missing.png")); }, file("missing.png"), "cannot open");

  const Image img = pattern(4, 4, 3);
  writePng(file("real.png"), img);
  writeExr(file("real.exr"), {{"", &img}});
  expectError([&] { readExr(file("real.png")); }, file("real.png"), "OpenEXR");
  expectError([&] { readPng(file("real.exr")); }, file("real.exr"), "not a PNG");
}

// Rewrites the dataWindow attribute of a file written by writeExr (the attribute's bytes are
// "dataWindow\0box2i\0", int32 size 16, then xMin yMin xMax yMax, little-endian).
void patchDataWindow(const std::string& path, int xMin, int yMin, int xMax, int yMax) {
  std::vector<char> bytes = readBytes(path);
  const char key[] = "dataWindow\0box2i\0";
  auto it = std::search(bytes.begin(), bytes.end(), key, key + sizeof key - 1);
  ASSERT_NE(it, bytes.end());
  const std::size_t at = std::size_t(it - bytes.begin()) + sizeof key - 1 + 4;
  const int box[4] = {xMin, yMin, xMax, yMax};
  std::memcpy(bytes.data() + at, box, sizeof box);
  writeBytes(path, bytes);
}

TEST_F(ImageIoTest, ExrHugeOrEmptyDataWindowIsRejectedFromTheHeader) {
  const Image img = pattern(8, 8, 3);
  const std::string path = file("huge.exr");
  writeExr(path, {{"", &img}});
  patchDataWindow(path, 0, 0, 16384, 7);  // 16385 wide
  expectError([&] { readExr(path); }, path, "larger than 16384x16384");
  writeExr(path, {{"", &img}});
  patchDataWindow(path, 0, 0, 7, 20000);
  expectError([&] { readExr(path); }, path, "larger than 16384x16384");
  writeExr(path, {{"", &img}});
  patchDataWindow(path, 0, 0, 7, (1 << 30));  // the header parser itself refuses this one
  expectError([&] { readExr(path); }, path);
  writeExr(path, {{"", &img}});
  patchDataWindow(path, -2000000000, 0, 2000000000, 7);  // width overflows int32
  expectError([&] { readExr(path); }, path);
  writeExr(path, {{"", &img}});
  patchDataWindow(path, 5, 0, 4, 7);
  expectError([&] { readExr(path); }, path);
}

TEST_F(ImageIoTest, ExrMultiPartAndDeepFilesAreRejected) {
  const std::string multi = file("multi.exr");
  {
    std::vector<Imf::Header> headers(2, Imf::Header(4, 4));
    for (int i = 0; i < 2; ++i) {
      headers[i].setName("part" + std::to_string(i));
      headers[i].setType(Imf::SCANLINEIMAGE);
      headers[i].channels().insert("R", Imf::Channel(Imf::FLOAT));
    }
    const Image img = pattern(4, 4, 1);
    Imf::MultiPartOutputFile out(multi.c_str(), headers.data(), 2);
    for (int i = 0; i < 2; ++i) {
      Imf::OutputPart part(out, i);
      Imf::FrameBuffer fb;
      fb.insert("R", Imf::Slice(Imf::FLOAT, (char*)img.data.data(), 4, 16));
      part.setFrameBuffer(fb);
      part.writePixels(4);
    }
  }
  expectError([&] { readExr(multi); }, multi, "multi-part");

  const std::string deep = file("deep.exr");
  {
    Imf::Header header(2, 2);
    header.setType(Imf::DEEPSCANLINE);
    header.compression() = Imf::ZIPS_COMPRESSION;
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    std::vector<unsigned> counts(4, 1);
    std::vector<float> samples(4, 0.5f);
    std::vector<float*> pointers = {&samples[0], &samples[1], &samples[2], &samples[3]};
    Imf::DeepFrameBuffer fb;
    fb.insertSampleCountSlice(Imf::Slice(Imf::UINT, (char*)counts.data(), sizeof(unsigned), 2 * sizeof(unsigned)));
    fb.insert("R",
              Imf::DeepSlice(Imf::FLOAT, (char*)pointers.data(), sizeof(float*), 2 * sizeof(float*), sizeof(float)));
    Imf::DeepScanLineOutputFile out(deep.c_str(), header);
    out.setFrameBuffer(fb);
    out.writePixels(2);
  }
  expectError([&] { readExr(deep); }, deep, "deep");
}

// ---------------------------------------------------------------------------------------------
// Unwritable paths, texture dispatch

TEST_F(ImageIoTest, UnwritablePathsThrowInsteadOfCrashing) {
  const Image img = pattern(4, 4, 3);
  std::vector<std::string> paths = {"/nonexistent/dir/x"};
  // A regular file used as a folder fails for every user, root included.
  writeBytes(file("plain"), {'x'});
  paths.push_back(file("plain") + "/x");
  const fs::path locked = dir_ / "locked";
  fs::create_directories(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  // Root ignores the mode bits, so a read-only folder is only a test case for other users.
  if (::access(locked.c_str(), W_OK) != 0) paths.push_back((locked / "x").string());
  for (const std::string& base : paths) {
    expectError([&] { writePng(base + ".png", img); }, base + ".png", "cannot write");
    expectError([&] { writeExr(base + ".exr", {{"", &img}}); }, base + ".exr", "cannot write");
  }
}

TEST_F(ImageIoTest, ReadTextureDispatchesOnCaseInsensitiveExtension) {
  const Image img = pattern(4, 4, 3);
  writeExr(file("a.EXR"), {{"", &img}});
  writePng(file("b.Png"), img);
  EXPECT_EQ(readTexture(file("a.EXR")).channels, 4);
  EXPECT_EQ(readTexture(file("b.Png")).channels, 4);
  writeBytes(file("c.jpg"), {'x'});
  expectError([&] { readTexture(file("c.jpg")); }, file("c.jpg"), "unsupported texture format");
  writeBytes(file("noext"), {'x'});
  expectError([&] { readTexture(file("noext")); }, file("noext"), "unsupported texture format");
}

}  // namespace
}  // namespace penumbra
