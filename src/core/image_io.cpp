// Image files by extension (core/image_io.h); the formats are exr_io.cpp and png_io.cpp.
#include "core/image_io.h"

#include <algorithm>
#include <cctype>

#include "core/error.h"
#include "core/log.h"

namespace penumbra {

namespace {

// ".exr", ".png" (lower case), or the refusal naming what the file's extension is.
std::string textureExtension(const std::string& path) {
  const std::size_t dot = path.rfind('.');
  const std::size_t slash = path.find_last_of('/');
  const bool hasExt = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  std::string ext = hasExt ? path.substr(dot) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".exr" || ext == ".png") return ext;
  throw Error(path, "unsupported texture format '" + (hasExt ? ext : "no extension") + "' (expected .exr or .png)");
}

}  // namespace

ImageHeader readImageHeader(const std::string& path) {
  return textureExtension(path) == ".exr" ? readExrHeader(path) : readPngHeader(path);
}

Image readTexture(const std::string& path, bool srgb) {
  if (textureExtension(path) == ".exr") {
    int sanitized = 0;
    Image img = readExr(path, &sanitized);
    if (sanitized > 0) PLOG_WARN("{}: replaced {} non-finite texels with 0", path, sanitized);
    return img;
  }
  return readPng(path, srgb);
}

}  // namespace penumbra
