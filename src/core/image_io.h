// Image files. EXR holds linear float data; PNG is tone-mapped sRGB for viewing.
// All readers validate before allocating and throw penumbra::Error("<path>", "<problem>").
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace penumbra {

// A named layer of an EXR file: channels are written as "<layer>.R", "<layer>.G", ... (an
// empty layer name writes plain "R", "G", "B", "A"). Channel names follow the image's channel
// count: 1 -> "Y", 3 -> RGB, 4 -> RGBA.
struct ExrLayer {
  std::string name;
  const Image* image = nullptr;
};

// Writes a multi-layer float32 EXR (all layers the same size). Throws on an unwritable path.
void writeExr(const std::string& path, const std::vector<ExrLayer>& layers);

// Reads an RGB(A) EXR texture (first RGB(A) channels found). Rejects deep / multi-part /
// truncated files and data windows over 16384^2; NaN/Inf texels are replaced by 0 and counted
// in *sanitized (if given).
Image readExr(const std::string& path, int* sanitized = nullptr);

// Reads one layer as written by writeExr ("" = unprefixed channels) with its own channel
// count: RGBA -> 4, RGB -> 3, Y -> 1. Same validation and sanitizing as readExr.
Image readExrLayer(const std::string& path, const std::string& layer, int* sanitized = nullptr);

// Writes an 8-bit sRGB PNG: linear value * 2^exposure, Reinhard-free clamp, sRGB OETF.
// 1-channel images are written as grey. Throws on an unwritable path.
void writePng(const std::string& path, const Image& linear, float exposure = 0.0f);

// Reads a PNG/JPEG-free 8-bit or 16-bit PNG as linear float RGBA (sRGB decoded when
// `srgb` is true).
Image readPng(const std::string& path, bool srgb = true);

// Reads a texture by extension (.exr or .png); other extensions are rejected.
Image readTexture(const std::string& path, bool srgb = true);

// The sides an image file declares, read from its header without decoding a pixel.
struct ImageHeader {
  int width = 0, height = 0;
};

// A texture file's header by extension (.png IHDR, .exr data window), validated as the readers
// validate it before they allocate; the readers also refuse what memory (core/memory.h) cannot
// hold before decoding.
ImageHeader readImageHeader(const std::string& path);
ImageHeader readExrHeader(const std::string& path);
ImageHeader readPngHeader(const std::string& path);

// A PNG's IHDR read from its first bytes (the signature, then the IHDR chunk): false when `bytes`
// do not start so. Shared by the file reader and glTF's embedded images.
struct PngIhdr {
  std::uint32_t width = 0, height = 0;
  int bitDepth = 0, colourType = 0;
};
bool readPngIhdr(const unsigned char* bytes, std::size_t n, PngIhdr& out);

// Non-empty (the reason) when `bytes` bytes of PNG cannot hold the `width` x `height` image of
// `bitDepth` and `colourType` its header declares: deflate compresses at most 1032:1 (RFC 1951's
// longest match, 258 bytes, in a code of at least 2 bits), so the rows' smallest raw size (a
// filter byte and the packed samples each) bounds the compressed data from below. A 71-byte file
// declaring 16000^2 is refused before anything is allocated for it.
std::string pngSizeProblem(std::int64_t width, std::int64_t height, int bitDepth, int colourType, std::uint64_t bytes);

}  // namespace penumbra
