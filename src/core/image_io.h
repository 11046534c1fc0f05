// Image files. EXR holds linear float data; PNG is tone-mapped sRGB for viewing.
// All readers validate before allocating and throw penumbra::Error("<path>", "<problem>").
#pragma once

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

}  // namespace penumbra
