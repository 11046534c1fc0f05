// PNG files (libpng): the 8-bit sRGB writer and the validating 8/16-bit reader of core/image_io.h.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include <png.h>

#include "core/color.h"
#include "core/error.h"
#include "core/files.h"
#include "core/image_io.h"
#include "core/image_io_detail.h"
#include "core/log.h"
#include "core/memory.h"

namespace penumbra {
using namespace image_io_detail;
namespace {

// State shared with libpng's callbacks. Everything here is trivially destructible because a
// libpng error longjmps over the frames in between.
struct PngIo {
  std::FILE* file = nullptr;
  png_structp png = nullptr;
  png_infop info = nullptr;
  char message[256] = {};
};

void pngError(png_structp png, png_const_charp msg) {
  auto* io = static_cast<PngIo*>(png_get_error_ptr(png));
  std::snprintf(io->message, sizeof io->message, "%s", msg ? msg : "libpng error");
  png_longjmp(png, 1);
}

void pngWarning(png_structp, png_const_charp msg) { PLOG_DEBUG("libpng: {}", msg ? msg : ""); }

using PngStep = void (*)(PngIo&, void*);

// Runs `step` and returns false if libpng raised an error. No object with a destructor lives
// between this setjmp and the longjmp in pngError, so jumping over the frames is well defined.
bool pngGuarded(PngIo& io, PngStep step, void* arg) {
  if (setjmp(png_jmpbuf(io.png))) return false;
  step(io, arg);
  return true;
}

struct PngWriteArgs {
  png_uint_32 width, height;
  int colorType;
  png_bytep* rows;
};

struct PngHeader {
  png_uint_32 width = 0, height = 0;
  int bitDepth = 0, colorType = 0;
  png_size_t rowBytes = 0;
  int channels = 0;
};

// The header's sides against the largest accepted and the file's size (pngSizeProblem).
void checkPngSize(const std::string& path, std::int64_t width, std::int64_t height, int bitDepth, int colourType) {
  if (width > kMaxDimension || height > kMaxDimension) {
    throw Error(path, "image " + sizeText(width, height) + " is larger than " + sizeText(kMaxDimension, kMaxDimension));
  }
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec) {
    if (const std::string why = pngSizeProblem(width, height, bitDepth, colourType, bytes); !why.empty())
      throw Error(path, why);
  }
}

std::uint32_t bigEndian32(const unsigned char* b) {
  return std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 | b[3];
}

}  // namespace

bool readPngIhdr(const unsigned char* b, std::size_t n, PngIhdr& out) {
  if (n < 26 || png_sig_cmp(b, 0, 8) != 0 || std::memcmp(b + 12, "IHDR", 4) != 0) return false;
  out = {bigEndian32(b + 16), bigEndian32(b + 20), b[24], b[25]};
  return true;
}

std::string pngSizeProblem(std::int64_t width, std::int64_t height, int bitDepth, int colourType, std::uint64_t bytes) {
  const int channels = colourType == PNG_COLOR_TYPE_RGB          ? 3
                       : colourType == PNG_COLOR_TYPE_RGB_ALPHA  ? 4
                       : colourType == PNG_COLOR_TYPE_GRAY_ALPHA ? 2
                                                                 : 1;
  const double raw = double(height) * (1.0 + std::ceil(double(width) * channels * std::max(bitDepth, 1) / 8.0));
  if (raw <= 1032.0 * double(bytes) + 1024.0) return {};
  return "declares " + sizeText(width, height) + " texels (" + std::to_string(std::int64_t(raw / 1048576.0)) +
         " MiB of rows) in " + std::to_string(bytes) +
         " bytes, more than deflate can compress into them: "
         "truncated or corrupt";
}

ImageHeader readPngHeader(const std::string& path) {
  FilePtr file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw Error(path, "cannot open: " + errnoText(errno));
  unsigned char b[26];
  const std::size_t got = std::fread(b, 1, sizeof b, file.get());
  if (got == 0) throw Error(path, "empty file, not a PNG image");
  if (got < 8 || png_sig_cmp(b, 0, 8) != 0) throw Error(path, "not a PNG file");
  PngIhdr h;
  if (!readPngIhdr(b, got, h)) throw Error(path, "invalid PNG file: no IHDR chunk first");
  if (h.width == 0 || h.height == 0)
    throw Error(path, "invalid PNG file: image of size " + sizeText(h.width, h.height));
  checkPngSize(path, h.width, h.height, h.bitDepth, h.colourType);
  return {int(h.width), int(h.height)};
}

void writePng(const std::string& path, const Image& linear, float exposure) {
  PENUMBRA_CHECK(!linear.empty() && linear.width > 0 && linear.height > 0, "writePng: empty image");
  PENUMBRA_CHECK(linear.channels >= 1 && linear.channels <= 4, "writePng: image needs 1 to 4 channels");
  PENUMBRA_CHECK(linear.data.size() == linear.pixelCount() * linear.channels,
                 "writePng: image data size does not match its dimensions");
  // 2-channel (grey + alpha) images are written as grey; alpha is dropped either way because
  // the PNG is a view of radiance, not a compositing layer.
  const int outChannels = linear.channels >= 3 ? 3 : 1;
  const float scale = std::exp2(exposure);
  std::vector<png_byte> pixels(linear.pixelCount() * outChannels);
  for (std::size_t p = 0; p < linear.pixelCount(); ++p) {
    for (int c = 0; c < outChannels; ++c) {
      float v = linear.data[p * linear.channels + c] * scale;
      v = v > 0.0f ? std::min(v, 1.0f) : 0.0f;  // also maps NaN to 0
      pixels[p * outChannels + c] = png_byte(std::lround(linearToSrgb(v) * 255.0f));
    }
  }
  std::vector<png_bytep> rows(linear.height);
  for (int y = 0; y < linear.height; ++y) {
    rows[y] = pixels.data() + std::size_t(y) * linear.width * outChannels;
  }

  writeAtomically(path, [&](const std::string& temporary) {
    errno = 0;
    std::FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file) throw Error(path, "cannot write: " + errnoText(errno));
    PngIo io;
    io.file = file;
    io.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &io, &pngError, &pngWarning);
    const bool created = io.png != nullptr;
    if (created) io.info = png_create_info_struct(io.png);
    PngWriteArgs args{png_uint_32(linear.width), png_uint_32(linear.height),
                      outChannels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, rows.data()};
    const bool ok =
        io.info && pngGuarded(
                       io,
                       [](PngIo& io, void* arg) {
                         const auto& a = *static_cast<PngWriteArgs*>(arg);
                         png_init_io(io.png, io.file);
                         png_set_IHDR(io.png, io.info, a.width, a.height, 8, a.colorType, PNG_INTERLACE_NONE,
                                      PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
                         png_set_sRGB(io.png, io.info, PNG_sRGB_INTENT_PERCEPTUAL);
                         png_write_info(io.png, io.info);
                         png_write_image(io.png, a.rows);
                         png_write_end(io.png, nullptr);
                       },
                       &args);
    if (io.png) png_destroy_write_struct(&io.png, &io.info);
    const bool closed = std::fclose(file) == 0;
    if (!ok || !closed) {
      const std::string why = !created || !ok ? (io.message[0] ? io.message : "out of memory") : errnoText(errno);
      throw Error(path, "cannot write PNG file: " + oneLine(why));
    }
  });
}

Image readPng(const std::string& path, bool srgb) {
  FilePtr file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw Error(path, "cannot open: " + errnoText(errno));
  png_byte signature[8];
  const std::size_t got = std::fread(signature, 1, sizeof signature, file.get());
  if (got == 0) throw Error(path, "empty file, not a PNG image");
  if (got != sizeof signature || png_sig_cmp(signature, 0, sizeof signature) != 0) {
    throw Error(path, "not a PNG file");
  }

  PngIo io;
  io.file = file.get();
  io.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &io, &pngError, &pngWarning);
  if (!io.png) throw Error(path, "cannot read PNG file: out of memory");
  io.info = png_create_info_struct(io.png);
  std::unique_ptr<PngIo, void (*)(PngIo*)> destroy(
      &io, [](PngIo* p) { png_destroy_read_struct(&p->png, &p->info, nullptr); });
  if (!io.info) throw Error(path, "cannot read PNG file: out of memory");

  PngHeader hdr;
  if (!pngGuarded(
          io,
          [](PngIo& io, void* arg) {
            auto& h = *static_cast<PngHeader*>(arg);
            png_init_io(io.png, io.file);
            png_set_sig_bytes(io.png, 8);
            png_read_info(io.png, io.info);
            png_get_IHDR(io.png, io.info, &h.width, &h.height, &h.bitDepth, &h.colorType, nullptr, nullptr, nullptr);
          },
          &hdr)) {
    throw Error(path, "invalid PNG file: " + oneLine(io.message));
  }
  checkPngSize(path, hdr.width, hdr.height, hdr.bitDepth, hdr.colorType);
  // The decode's peak: 8- or 16-bit RGBA rows, then float RGBA.
  checkMemory(path, "decoding its " + sizeText(hdr.width, hdr.height) + " texels",
              double(hdr.width) * double(hdr.height) * (hdr.bitDepth == 16 ? 24.0 : 20.0));

  // Every layout becomes 8- or 16-bit RGBA: palette/low-bit grey/tRNS expand, grey widens to
  // RGB, and a missing alpha is filled opaque.
  if (!pngGuarded(
          io,
          [](PngIo& io, void* arg) {
            auto& h = *static_cast<PngHeader*>(arg);
            png_set_expand(io.png);
            png_set_gray_to_rgb(io.png);
            const bool hasAlpha =
                (h.colorType & PNG_COLOR_MASK_ALPHA) != 0 || png_get_valid(io.png, io.info, PNG_INFO_tRNS) != 0;
            if (!hasAlpha) png_set_add_alpha(io.png, 0xffff, PNG_FILLER_AFTER);
            png_set_interlace_handling(io.png);
            png_read_update_info(io.png, io.info);
            h.bitDepth = png_get_bit_depth(io.png, io.info);
            h.channels = png_get_channels(io.png, io.info);
            h.rowBytes = png_get_rowbytes(io.png, io.info);
          },
          &hdr)) {
    throw Error(path, "invalid PNG file: " + oneLine(io.message));
  }
  const int bytesPerSample = hdr.bitDepth / 8;
  if (hdr.channels != 4 || (hdr.bitDepth != 8 && hdr.bitDepth != 16) ||
      hdr.rowBytes != png_size_t(hdr.width) * 4 * bytesPerSample) {
    throw Error(path, "unsupported PNG layout");
  }

  std::vector<png_byte> pixels(hdr.rowBytes * hdr.height);
  std::vector<png_bytep> rows(hdr.height);
  for (png_uint_32 y = 0; y < hdr.height; ++y) rows[y] = pixels.data() + y * hdr.rowBytes;
  if (!pngGuarded(
          io,
          [](PngIo& io, void* arg) {
            png_read_image(io.png, static_cast<png_bytep*>(arg));
            png_read_end(io.png, nullptr);
          },
          rows.data())) {
    throw Error(path, "truncated or corrupt PNG file: " + oneLine(io.message));
  }

  Image img(int(hdr.width), int(hdr.height), 4);
  auto colour = [srgb](float v) { return srgb ? srgbToLinear(v) : v; };
  if (bytesPerSample == 1) {
    float lut[256];
    for (int i = 0; i < 256; ++i) lut[i] = colour(float(i) / 255.0f);
    for (std::size_t i = 0; i < img.data.size(); ++i) {
      img.data[i] = (i % 4 == 3) ? float(pixels[i]) / 255.0f : lut[pixels[i]];
    }
  } else {
    for (std::size_t i = 0; i < img.data.size(); ++i) {
      const float v = float((pixels[2 * i] << 8) | pixels[2 * i + 1]) / 65535.0f;  // big-endian
      img.data[i] = (i % 4 == 3) ? v : colour(v);
    }
  }
  return img;
}

}  // namespace penumbra
