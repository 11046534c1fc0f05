// OpenEXR files: the multi-layer float writer and the validating readers of core/image_io.h.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCheckFile.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/openexr.h>

#include "core/error.h"
#include "core/files.h"
#include "core/image_io.h"
#include "core/image_io_detail.h"
#include "core/log.h"
#include "core/memory.h"

namespace penumbra {
using namespace image_io_detail;
namespace {

// The core library reports errors through a callback (default: stderr); keep the last one.
thread_local std::string tExrCoreMessage;

void exrCoreError(exr_const_context_t, exr_result_t, const char* msg) { tExrCoreMessage = msg ? msg : ""; }

// OpenEXR's C++ header reader (checkOpenEXRFile, Imf::InputFile) trusts the file: it
// allocates an unknown attribute's declared size before reading it (a 1.7 KB file declaring
// 1.6 GB, found by fuzzing: tests/fuzz/regressions/exr/), and it reads a known type by its own
// layout (a chlist until its empty name, a preview by its width x height) rather than by the
// declared size, so a size that disagrees makes it read the rest of the header out of step.
// Both are checked here, in the reader's own walk of the (single) header: every size fits in
// the file, and every known type's content has exactly its declared size. Layout: magic,
// version, then (name\0 type\0 int32 size value) per attribute, ended by an empty name.
void checkExrAttributeSizes(const std::string& path) {
  // The header is read whole; 64 MiB is far beyond any real one (a preview image included).
  constexpr std::size_t kMaxHeader = 64u << 20;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff fileSize = in.tellg();
  std::string bytes(std::min<std::size_t>(fileSize > 0 ? std::size_t(fileSize) : 0, kMaxHeader), '\0');
  in.seekg(0);
  in.read(bytes.data(), std::streamsize(bytes.size()));
  bytes.resize(std::size_t(in.gcount()));
  const auto u8 = [&](std::size_t at) { return std::uint32_t(static_cast<unsigned char>(bytes[at])); };
  const auto i32 = [&](std::size_t at) {
    return std::int64_t(std::int32_t(u8(at) | u8(at + 1) << 8 | u8(at + 2) << 16 | u8(at + 3) << 24));
  };
  if (bytes.size() < 8) throw Error(path, "truncated OpenEXR header");
  const std::size_t maxName = (u8(5) & 0x04) ? 255 : 31;  // long-names flag, version bit 10
  std::size_t pos = 8;
  auto readString = [&](const char* what) {
    const std::size_t end = bytes.find('\0', pos);
    if (end == std::string::npos) throw Error(path, "truncated OpenEXR header");
    if (end - pos > maxName) throw Error(path, std::string("OpenEXR ") + what + " too long");
    std::string out = bytes.substr(pos, end - pos);
    pos = end + 1;
    return out;
  };
  // Known types of fixed size (OpenEXR 3.1's TypedAttribute layouts).
  static const std::map<std::string, std::int64_t> kFixed = {{"box2i", 16},
                                                             {"box2f", 16},
                                                             {"compression", 1},
                                                             {"lineOrder", 1},
                                                             {"envmap", 1},
                                                             {"float", 4},
                                                             {"double", 8},
                                                             {"int", 4},
                                                             {"v2i", 8},
                                                             {"v2f", 8},
                                                             {"v2d", 16},
                                                             {"v3i", 12},
                                                             {"v3f", 12},
                                                             {"v3d", 24},
                                                             {"m33f", 36},
                                                             {"m44f", 64},
                                                             {"m33d", 72},
                                                             {"m44d", 128},
                                                             {"chromaticities", 32},
                                                             {"keycode", 28},
                                                             {"timecode", 8},
                                                             {"rational", 8},
                                                             {"tiledesc", 9},
                                                             {"deepImageState", 1}};
  for (int count = 0; count < 10000; ++count) {
    const std::string name = readString("attribute name");
    if (name.empty()) return;
    const std::string type = readString("attribute type");
    if (bytes.size() - pos < 4) throw Error(path, "truncated OpenEXR header");
    const std::int64_t size = i32(pos);
    pos += 4;
    const std::string what = "OpenEXR header attribute '" + oneLine(name) + "' (" + oneLine(type) + ")";
    if (size < 0 || std::uint64_t(size) > bytes.size() - pos) {
      if (bytes.size() == kMaxHeader) throw Error(path, "OpenEXR header larger than 64 MiB");
      throw Error(path, what + " declares " + std::to_string(size) + " bytes, more than the " +
                            std::to_string(bytes.size() - pos) + " left in the file");
    }
    std::int64_t content = size;  // what the C++ reader will consume
    if (const auto it = kFixed.find(type); it != kFixed.end()) {
      content = it->second;
    } else if (type == "chlist") {  // entries: name\0 and 16 bytes, then an empty name
      std::size_t at = pos;
      while (at < pos + std::size_t(size) && bytes[at] != 0) {
        const std::size_t end = bytes.find('\0', at);
        if (end == std::string::npos || end - at > 255) break;  // channel names: any length
        at = end + 1 + 16;
      }
      content = std::int64_t(at - pos) + 1;
    } else if (type == "preview") {  // width, height, then 4 bytes per pixel
      const long double pixels = size >= 8 ? (long double)i32(pos) * i32(pos + 4) : -1.0L;
      content = pixels >= 0 && 8 + 4 * pixels == size ? size : -1;
    } else if (type == "stringvector") {  // (int32 length, chars)*, each read into a string
      std::int64_t at = 0;
      while (at + 4 <= size) {
        const std::int64_t n = i32(pos + std::size_t(at));
        if (n < 0 || n > size - at - 4) break;
        at += 4 + n;
      }
      content = at;
    }
    if (content != size) {
      throw Error(
          path, what + " declares " + std::to_string(size) + " bytes but its content needs " + std::to_string(content));
    }
    pos += std::size_t(size);
  }
  throw Error(path, "OpenEXR header has too many attributes");
}

// Validates everything that decides how much memory a read will take, before any reader
// allocates: the core API parses only the header (the chunk table is read lazily), whereas
// Imf::InputFile sizes its line-offset table from the data window straight away.
ImageHeader exrHeader(const std::string& path) {
  {
    FilePtr probe(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!probe) throw Error(path, "cannot open: " + errnoText(errno));
  }
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = &exrCoreError;
  exr_context_t ctx = nullptr;
  tExrCoreMessage.clear();
  exr_result_t rv = exr_start_read(&ctx, path.c_str(), &init);
  std::unique_ptr<exr_context_t, void (*)(exr_context_t*)> guard(&ctx, [](exr_context_t* c) { exr_finish(c); });
  if (rv != EXR_ERR_SUCCESS) {
    std::string why = tExrCoreMessage.empty() ? exr_get_default_error_message(rv) : tExrCoreMessage;
    throw Error(path, "not a valid OpenEXR file (" + oneLine(why) + ")");
  }
  int parts = 0;
  exr_storage_t storage = EXR_STORAGE_SCANLINE;
  exr_attr_box2i_t dw{};
  if (exr_get_count(ctx, &parts) != EXR_ERR_SUCCESS || exr_get_storage(ctx, 0, &storage) != EXR_ERR_SUCCESS ||
      exr_get_data_window(ctx, 0, &dw) != EXR_ERR_SUCCESS) {
    throw Error(path, "not a valid OpenEXR file (unreadable header)");
  }
  if (parts != 1) throw Error(path, "multi-part OpenEXR files are not supported");
  if (storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED) {
    throw Error(path, "deep OpenEXR files are not supported");
  }
  const std::int64_t w = std::int64_t(dw.max.x) - dw.min.x + 1;
  const std::int64_t h = std::int64_t(dw.max.y) - dw.min.y + 1;
  if (w <= 0 || h <= 0) throw Error(path, "empty data window");
  if (w > kMaxDimension || h > kMaxDimension) {
    throw Error(path, "data window " + sizeText(w, h) + " is larger than " + sizeText(kMaxDimension, kMaxDimension));
  }
  return {int(w), int(h)};
}

void checkExrFile(const std::string& path) {
  const ImageHeader header = exrHeader(path);
  // Float RGBA texels; OpenEXR's own line buffers are a few lines.
  checkMemory(path, "decoding its " + sizeText(header.width, header.height) + " texels",
              double(header.width) * double(header.height) * 16.0);
  checkExrAttributeSizes(path);
  // reduceMemory/reduceTime bound what the check itself may allocate and read.
  if (Imf::checkOpenEXRFile(path.c_str(), /*reduceMemory=*/true, /*reduceTime=*/true)) {
    throw Error(path, "corrupt or truncated OpenEXR file");
  }
}

struct LayerChannels {
  bool r = false, g = false, b = false, a = false, y = false;
  bool rgb() const { return r && g && b; }
};

// Layers by name ("" = unprefixed channels); std::map keeps "" first, then alphabetical.
std::map<std::string, LayerChannels> exrLayers(const Imf::Header& header) {
  std::map<std::string, LayerChannels> layers;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    const std::string name = it.name();
    const std::size_t dot = name.rfind('.');
    const std::string layer = dot == std::string::npos ? "" : name.substr(0, dot);
    const std::string suffix = dot == std::string::npos ? name : name.substr(dot + 1);
    LayerChannels& l = layers[layer];
    const bool subsampled = it.channel().xSampling != 1 || it.channel().ySampling != 1;
    bool* flag = suffix == "R"   ? &l.r
                 : suffix == "G" ? &l.g
                 : suffix == "B" ? &l.b
                 : suffix == "A" ? &l.a
                 : suffix == "Y" ? &l.y
                                 : nullptr;
    // A subsampled channel cannot be read into a full-resolution float buffer; ignore it so
    // the layer is rejected (or skipped) as lacking that channel.
    if (flag && !subsampled) *flag = true;
  }
  return layers;
}

std::string prefixed(const std::string& layer, const char* channel) {
  return layer.empty() ? std::string(channel) : layer + "." + channel;
}

// Which file channel goes to which output channel; "" leaves that channel at its `fills` value.
struct ChannelPlan {
  std::vector<std::string> names;
  std::vector<float> fills;
  bool greyToRgb = false;  // copy output channel 0 into 1 and 2
};

using Planner = ChannelPlan (*)(const std::string& path, const std::map<std::string, LayerChannels>& layers,
                                const std::string& layer);

Image readExrWith(const std::string& path, Planner planner, const std::string& layer, int* sanitized) {
  checkExrFile(path);
  Image img;
  ChannelPlan plan;
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    const std::int64_t w = std::int64_t(dw.max.x) - dw.min.x + 1;
    const std::int64_t h = std::int64_t(dw.max.y) - dw.min.y + 1;
    // Checked in checkExrFile already; repeated in case the file changed since.
    if (w <= 0 || h <= 0 || w > kMaxDimension || h > kMaxDimension) {
      throw Error(path, "data window " + sizeText(w, h) + " is empty or too large");
    }
    plan = planner(path, exrLayers(file.header()), layer);
    const int c = int(plan.names.size());
    img = Image(int(w), int(h), c, 0.0f);
    Imf::FrameBuffer fb;
    const std::size_t xStride = sizeof(float) * c;
    for (int i = 0; i < c; ++i) {
      if (plan.names[i].empty()) {
        for (std::size_t p = 0; p < img.pixelCount(); ++p) img.data[p * c + i] = plan.fills[i];
        continue;
      }
      fb.insert(plan.names[i],
                Imf::Slice::Make(Imf::FLOAT, img.data.data() + i, dw, xStride, xStride * w, 1, 1, plan.fills[i]));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path, "cannot read OpenEXR file: " + oneLine(e.what()));
  }
  int bad = 0;
  for (std::size_t p = 0; p < img.pixelCount(); ++p) {
    bool texelBad = false;
    for (int i = 0; i < img.channels; ++i) {
      float& v = img.data[p * img.channels + i];
      if (!std::isfinite(v)) {
        v = 0.0f;
        texelBad = true;
      }
    }
    bad += texelBad ? 1 : 0;
  }
  if (plan.greyToRgb) {
    for (std::size_t p = 0; p < img.pixelCount(); ++p) {
      float* px = &img.data[p * img.channels];
      px[1] = px[2] = px[0];
    }
  }
  if (sanitized) *sanitized = bad;
  return img;
}

}  // namespace

void writeExr(const std::string& path, const std::vector<ExrLayer>& layers) {
  PENUMBRA_CHECK(!layers.empty(), "writeExr needs at least one layer");
  PENUMBRA_CHECK(layers.front().image != nullptr, "writeExr: null image");
  const int w = layers.front().image->width;
  const int h = layers.front().image->height;
  PENUMBRA_CHECK(w > 0 && h > 0, "writeExr: empty image");
  Imf::Header header(w, h);
  header.compression() = Imf::ZIP_COMPRESSION;
  Imf::FrameBuffer fb;
  for (const ExrLayer& layer : layers) {
    const Image* img = layer.image;
    PENUMBRA_CHECK(img != nullptr, "writeExr: null image in layer " + layer.name);
    PENUMBRA_CHECK(img->width == w && img->height == h, "writeExr: layer sizes differ");
    PENUMBRA_CHECK(img->channels == 1 || img->channels == 3 || img->channels == 4,
                   "writeExr: layer " + layer.name + " needs 1, 3 or 4 channels");
    PENUMBRA_CHECK(img->data.size() == img->pixelCount() * img->channels,
                   "writeExr: image data size does not match its dimensions");
    static const char* const kRgba[] = {"R", "G", "B", "A"};
    const std::size_t xStride = sizeof(float) * img->channels;
    for (int c = 0; c < img->channels; ++c) {
      const std::string name = prefixed(layer.name, img->channels == 1 ? "Y" : kRgba[c]);
      PENUMBRA_CHECK(header.channels().findChannel(name) == nullptr, "writeExr: duplicate channel " + name);
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      // OpenEXR's Slice wants a mutable pointer even for writing; it only reads.
      char* base = reinterpret_cast<char*>(const_cast<float*>(img->data.data() + c));
      fb.insert(name, Imf::Slice(Imf::FLOAT, base, xStride, xStride * w));
    }
  }

  writeAtomically(path, [&](const std::string& temporary) {
    errno = 0;
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path, "cannot write: " + errnoText(errno));
    try {
      Imf::StdOFStream stream(out, path.c_str());
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(fb);
      file.writePixels(h);
    } catch (const std::exception& e) {
      throw Error(path, "cannot write OpenEXR file: " + oneLine(e.what()));
    }
    // ~OutputFile writes the line-offset table and swallows failures; the stream state does not.
    out.close();
    if (out.fail()) throw Error(path, "cannot write OpenEXR file: write failed");
  });
}

Image readExr(const std::string& path, int* sanitized) {
  // First layer in exrLayers order with R,G,B, else the first with Y (read as grey).
  Planner plan = [](const std::string& path, const std::map<std::string, LayerChannels>& layers,
                    const std::string&) -> ChannelPlan {
    for (const auto& [p, l] : layers) {
      if (!l.rgb()) continue;
      return {{prefixed(p, "R"), prefixed(p, "G"), prefixed(p, "B"), l.a ? prefixed(p, "A") : ""},
              {0.0f, 0.0f, 0.0f, 1.0f}};
    }
    for (const auto& [p, l] : layers) {
      if (!l.y) continue;
      return {{prefixed(p, "Y"), "", "", l.a ? prefixed(p, "A") : ""}, {0.0f, 0.0f, 0.0f, 1.0f}, true};
    }
    throw Error(path, "no R,G,B or Y channels");
  };
  return readExrWith(path, plan, "", sanitized);
}

ImageHeader readExrHeader(const std::string& path) { return exrHeader(path); }

Image readExrLayer(const std::string& path, const std::string& layer, int* sanitized) {
  Planner plan = [](const std::string& path, const std::map<std::string, LayerChannels>& layers,
                    const std::string& layer) -> ChannelPlan {
    const auto it = layers.find(layer);
    if (it != layers.end() && it->second.rgb()) {
      ChannelPlan plan{{prefixed(layer, "R"), prefixed(layer, "G"), prefixed(layer, "B")}, {}};
      if (it->second.a) plan.names.push_back(prefixed(layer, "A"));
      plan.fills.assign(plan.names.size(), 0.0f);
      return plan;
    }
    if (it != layers.end() && it->second.y) return {{prefixed(layer, "Y")}, {0.0f}};
    throw Error(path, "no layer '" + layer + "' with R,G,B or Y channels");
  };
  return readExrWith(path, plan, layer, sanitized);
}
}  // namespace penumbra
