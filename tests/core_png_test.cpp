// PNG files: sRGB round trip, every layout readPng accepts, truncation and size limits.
#include <gtest/gtest.h>

#include "test_util.h"

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <png.h>

#include "core/error.h"
#include "core/image_io.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using test::expectError;

std::vector<unsigned char> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

float toSrgb(float v) { return v <= 0.0031308f ? v * 12.92f : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f; }

float fromSrgb(float s) { return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f); }

// Writes a PNG exactly as given (colour type, depth, palette, tRNS, interlace) with libpng.
struct RawPng {
  int width = 0, height = 0, colorType = PNG_COLOR_TYPE_RGB, bitDepth = 8;
  bool interlaced = false;
  std::vector<png_color> palette;
  std::vector<png_byte> paletteAlpha;
  std::vector<std::vector<png_byte>> rows;  // packed rows in file byte order

  void write(const std::string& path) const {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_set_IHDR(png, info, width, height, bitDepth, colorType, interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (!palette.empty()) png_set_PLTE(png, info, palette.data(), int(palette.size()));
    if (!paletteAlpha.empty()) {
      png_set_tRNS(png, info, paletteAlpha.data(), int(paletteAlpha.size()), nullptr);
    }
    png_write_info(png, info);
    std::vector<png_bytep> pointers;
    for (const auto& row : rows) pointers.push_back(const_cast<png_bytep>(row.data()));
    png_write_image(png, pointers.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
  }
};

std::uint32_t crc32(const unsigned char* p, std::size_t n) {
  std::uint32_t crc = 0xffffffffu;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void putBigEndian(unsigned char* p, std::uint32_t v) { p[0] = v >> 24, p[1] = v >> 16, p[2] = v >> 8, p[3] = v; }

using PngTest = test::TempDirTest;

TEST_F(PngTest, RoundTripIsWithinOneStepAfterSrgb) {
  Image img(17, 9, 3);
  for (std::size_t i = 0; i < img.data.size(); ++i) img.data[i] = float(i % 97) / 96.0f;
  img.data[0] = 0.0005f;  // linear part of the sRGB curve
  const std::string path = file("rt.png");
  writePng(path, img);
  const Image back = readPng(path);
  ASSERT_EQ(back.width, 17);
  ASSERT_EQ(back.height, 9);
  ASSERT_EQ(back.channels, 4);
  for (int y = 0; y < 9; ++y) {
    for (int x = 0; x < 17; ++x) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(toSrgb(back.at(x, y, c)), toSrgb(img.at(x, y, c)), 1.0f / 255.0f) << x << "," << y << "," << c;
      }
      EXPECT_EQ(back.at(x, y, 3), 1.0f);
    }
  }
  // srgb=false returns the stored code values.
  const Image raw = readPng(path, false);
  EXPECT_NEAR(raw.at(16, 8, 0), toSrgb(img.at(16, 8, 0)), 0.5f / 255.0f);
}

TEST_F(PngTest, ExposureClampAndGreyOutput) {
  Image img(4, 1, 1);
  img.data = {0.25f, 2.0f, -1.0f, std::numeric_limits<float>::quiet_NaN()};
  const std::string path = file("grey.png");
  writePng(path, img, 1.0f);  // x2
  const Image back = readPng(path);
  ASSERT_EQ(back.channels, 4);
  const float expected[4] = {0.5f, 1.0f, 0.0f, 0.0f};
  for (int x = 0; x < 4; ++x) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.at(x, 0, c), expected[x], 0.01f) << x;
  }
  const std::vector<unsigned char> bytes = readBytes(path);
  EXPECT_EQ(bytes[8 + 8 + 9], PNG_COLOR_TYPE_GRAY);  // IHDR colour type byte
}

TEST_F(PngTest, ReadsEveryLayoutAsLinearRgba) {
  {  // 16-bit RGB, big-endian samples
    RawPng p{2, 1, PNG_COLOR_TYPE_RGB, 16};
    p.rows = {{0x00, 0x00, 0xff, 0xff, 0x80, 0x00, 0x12, 0x34, 0x00, 0x01, 0xff, 0xfe}};
    p.write(file("rgb16.png"));
    const Image img = readPng(file("rgb16.png"), false);
    EXPECT_EQ(img.at(0, 0, 0), 0.0f);
    EXPECT_EQ(img.at(0, 0, 1), 1.0f);
    EXPECT_FLOAT_EQ(img.at(0, 0, 2), 32768.0f / 65535.0f);
    EXPECT_FLOAT_EQ(img.at(1, 0, 0), float(0x1234) / 65535.0f);
    EXPECT_EQ(img.at(1, 0, 3), 1.0f);
    const Image lin = readPng(file("rgb16.png"), true);
    EXPECT_NEAR(lin.at(0, 0, 2), fromSrgb(32768.0f / 65535.0f), 1e-6f);
  }
  {  // 16-bit RGBA
    RawPng p{1, 1, PNG_COLOR_TYPE_RGB_ALPHA, 16};
    p.rows = {{0xff, 0xff, 0x00, 0x00, 0x00, 0x00, 0x40, 0x00}};
    p.write(file("rgba16.png"));
    const Image img = readPng(file("rgba16.png"));
    EXPECT_EQ(img.at(0, 0, 0), 1.0f);
    EXPECT_FLOAT_EQ(img.at(0, 0, 3), 16384.0f / 65535.0f);  // alpha is never sRGB-decoded
  }
  {  // 8-bit grey + alpha
    RawPng p{1, 1, PNG_COLOR_TYPE_GRAY_ALPHA, 8};
    p.rows = {{128, 64}};
    p.write(file("ga.png"));
    const Image img = readPng(file("ga.png"));
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(img.at(0, 0, c), fromSrgb(128.0f / 255.0f));
    EXPECT_FLOAT_EQ(img.at(0, 0, 3), 64.0f / 255.0f);
  }
  {  // 1-bit grey
    RawPng p{4, 1, PNG_COLOR_TYPE_GRAY, 1};
    p.rows = {{0xa0}};  // 1010
    p.write(file("g1.png"));
    const Image img = readPng(file("g1.png"));
    const float expected[4] = {1.0f, 0.0f, 1.0f, 0.0f};
    for (int x = 0; x < 4; ++x) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(x, 0, c), expected[x]);
      EXPECT_EQ(img.at(x, 0, 3), 1.0f);
    }
  }
  {  // 4-bit palette with tRNS
    RawPng p{2, 1, PNG_COLOR_TYPE_PALETTE, 4};
    p.palette = {{255, 0, 0}, {0, 0, 255}};
    p.paletteAlpha = {255, 51};
    p.rows = {{0x10}};  // indices 1, 0
    p.write(file("pal.png"));
    const Image img = readPng(file("pal.png"), false);
    EXPECT_EQ(img.at(0, 0, 2), 1.0f);
    EXPECT_EQ(img.at(0, 0, 0), 0.0f);
    EXPECT_FLOAT_EQ(img.at(0, 0, 3), 0.2f);
    EXPECT_EQ(img.at(1, 0, 0), 1.0f);
    EXPECT_EQ(img.at(1, 0, 3), 1.0f);
  }
  {  // interlaced 8-bit RGB
    RawPng p{9, 9, PNG_COLOR_TYPE_RGB, 8};
    p.interlaced = true;
    for (int y = 0; y < 9; ++y) {
      std::vector<png_byte> row;
      for (int x = 0; x < 9; ++x) row.insert(row.end(), {png_byte(x * 20), png_byte(y * 20), 7});
      p.rows.push_back(row);
    }
    p.write(file("adam7.png"));
    const Image img = readPng(file("adam7.png"), false);
    for (int y = 0; y < 9; ++y) {
      for (int x = 0; x < 9; ++x) {
        EXPECT_FLOAT_EQ(img.at(x, y, 0), float(x * 20) / 255.0f);
        EXPECT_FLOAT_EQ(img.at(x, y, 1), float(y * 20) / 255.0f);
      }
    }
  }
}

TEST_F(PngTest, TruncatedFilesAreRejected) {
  Image img(32, 32, 3);
  for (std::size_t i = 0; i < img.data.size(); ++i) img.data[i] = float((i * 7919) % 256) / 255.f;
  const std::string path = file("t.png");
  writePng(path, img);
  const std::vector<unsigned char> full = readBytes(path);
  for (std::size_t keep : {full.size() - 1, full.size() / 2, std::size_t(20), std::size_t(5)}) {
    writeBytes(path, std::vector<unsigned char>(full.begin(), full.begin() + keep));
    expectError([&] { readPng(path); }, path);
  }
  // A flipped bit in the image data fails its CRC.
  std::vector<unsigned char> corrupt = full;
  corrupt[full.size() / 2] ^= 0x10;
  writeBytes(path, corrupt);
  expectError([&] { readPng(path); }, path);
}

TEST_F(PngTest, OversizedHeaderIsRejectedBeforeAllocating) {
  const std::string path = file("huge.png");
  writePng(path, Image(1, 1, 3, 0.5f));
  for (std::uint32_t size : {16385u, 1000000u}) {
    std::vector<unsigned char> bytes = readBytes(path);
    putBigEndian(&bytes[16], size);                   // IHDR width
    putBigEndian(&bytes[20], size);                   // IHDR height
    putBigEndian(&bytes[29], crc32(&bytes[12], 17));  // CRC over type + 13 data bytes
    writeBytes(path, bytes);
    expectError([&] { readPng(path); }, path, "larger than 16384x16384");
  }
}

}  // namespace
}  // namespace penumbra
