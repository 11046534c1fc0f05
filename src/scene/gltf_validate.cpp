// Everything about a glTF file that must be checked before tinygltf sees it. tinygltf 2.7
// trusts bufferView bounds when it decodes embedded images, lets a GLB BIN chunk run 8 bytes
// past the declared length, falls back to the working directory for relative URIs and
// allocates what a data: URI decodes to; so the container, the URIs and the sizes are checked
// here, and tinygltf's file access goes through callbacks confined to the file's folder.
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/color.h"
#include "core/error.h"
#include "core/image_io.h"
#include "scene/gltf_compression.h"
#include "scene/loaders.h"

namespace penumbra::detail {

namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kMaxFileBytes = 1ull << 30;  // tinygltf takes 32-bit lengths
constexpr std::uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;
constexpr std::uint32_t kChunkBin = 0x004E4942;
constexpr int kMaxImageSide = 8192;

// The data: URI headers tinygltf decodes; anything else it would treat as a file name.
const char* const kDataUriHeaders[] = {"data:application/octet-stream;base64,",
                                       "data:application/gltf-buffer;base64,",
                                       "data:image/jpeg;base64,",
                                       "data:image/png;base64,",
                                       "data:image/bmp;base64,",
                                       "data:image/gif;base64,",
                                       "data:text/plain;base64,"};

std::uint32_t readU32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

std::vector<unsigned char> readBinary(const std::string& path) {
  if (const std::string why = fileProblem(path); !why.empty()) throw Error(path, why);
  std::error_code ec;
  const std::uint64_t size = fs::file_size(path, ec);
  if (ec) throw Error(path, "cannot read: " + ec.message());
  if (size == 0) throw Error(path, "empty file");
  if (size > kMaxFileBytes) throw Error(path, "larger than 1 GiB");
  std::vector<unsigned char> bytes(size);
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size))) {
    throw Error(path, "cannot read the whole file");
  }
  return bytes;
}

// Same decoding as tinygltf's (dlib's) urldecode, so the check sees the name it will open.
std::string urlDecode(const std::string& s) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return 0;
  };
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out += ' ';
    } else if (s[i] == '%' && s.size() > i + 2) {
      out += char(hex(s[i + 1]) << 4 | hex(s[i + 2]));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

// Decoded size of strict base64 (no whitespace, '=' only as final padding), or -1.
long long base64DecodedSize(const std::string& s, std::size_t start) {
  const std::size_t n = s.size() - start;
  if (n == 0 || n % 4 != 0) return -1;
  std::size_t padding = 0;
  for (std::size_t i = start; i < s.size(); ++i) {
    const char c = s[i];
    const bool alpha =
        (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' || c == '/';
    if (c == '=') {
      if (i + 2 < s.size()) return -1;
      ++padding;
    } else if (!alpha || padding > 0) {
      return -1;
    }
  }
  return static_cast<long long>(n / 4 * 3 - padding);
}

struct Sandbox {
  std::string folder;
};

bool sandboxFileExists(const std::string& path, void* user) {
  const auto* box = static_cast<const Sandbox*>(user);
  std::error_code ec;
  return isInsideFolder(path, box->folder) && fs::is_regular_file(path, ec);
}

std::string sandboxExpand(const std::string& path, void*) { return path; }

bool sandboxRead(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const auto* box = static_cast<const Sandbox*>(user);
  if (!isInsideFolder(path, box->folder)) {
    if (err) *err += "'" + path + "' is outside the glTF file's folder";
    return false;
  }
  std::error_code ec;
  const std::uint64_t size = fs::file_size(path, ec);
  if (ec || size > kMaxFileBytes) {
    if (err) *err += ec ? ec.message() : std::string("larger than 1 GiB");
    return false;
  }
  out->resize(size);
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(out->data()), std::streamsize(size))) {
    if (err) *err += "cannot read '" + path + "'";
    return false;
  }
  return true;
}

bool sandboxWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not allowed";
  return false;
}

// Keeps images encoded: only base-colour textures are decoded later, and a broken normal map
// must not fail the load.
bool keepEncoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                 int size, void*) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

struct Checker {
  std::string path;
  std::string folder;
  const Json& doc;
  std::vector<std::string>& warnings;
  std::uint64_t binChunkBytes = 0;  // 0: no BIN chunk
  bool glb = false;

  [[noreturn]] void fail(const std::string& what) const { throw Error(path, what); }

  const Json* arrayOf(const char* key) const {
    const auto it = doc.find(key);
    if (it == doc.end()) return nullptr;
    if (!it->is_array()) fail(std::string("'") + key + "' must be an array");
    for (const Json& item : *it) {
      if (!item.is_object()) fail(std::string("'") + key + "' must hold JSON objects");
    }
    return &*it;
  }

  static bool unsignedField(const Json& o, const char* key, std::uint64_t& out) {
    const auto it = o.find(key);
    if (it == o.end()) return false;
    if (!it->is_number_unsigned() && !(it->is_number_integer() && it->get<long long>() >= 0)) {
      out = std::numeric_limits<std::uint64_t>::max();
      return true;
    }
    out = it->get<std::uint64_t>();
    return true;
  }

  void checkVersion() const {
    // glTF 1.0 keeps its objects in dictionaries keyed by id, where 2.0 has arrays.
    for (const char* key : {"meshes", "nodes", "accessors", "buffers", "bufferViews", "materials"})
      if (const auto it = doc.find(key); it != doc.end() && it->is_object())
        fail(std::string("a glTF 1.0 file ('") + key +
             "' is a dictionary): only glTF 2.0 is read; convert it (Blender, or gltf-pipeline's 1.0-to-2.0 upgrade)");
    const auto asset = doc.find("asset");
    if (asset == doc.end() || !asset->is_object()) fail("no 'asset' object: not a glTF 2.0 file");
    const auto version = asset->find("version");
    if (version == asset->end()) fail("'asset.version' missing: not a glTF 2.0 file");
    if (!version->is_string()) fail("'asset.version' must be a string (\"2.0\"), got " + shownJson(*version));
    const std::string v = version->get<std::string>();
    if (v.rfind("2.", 0) != 0) fail("glTF version " + v + " is not supported (2.x only)");
  }

  void checkExtensions() const {
    const auto it = doc.find("extensionsRequired");
    if (it == doc.end()) return;
    if (!it->is_array()) fail("'extensionsRequired' must be an array");
    for (const Json& e : *it) {
      if (!e.is_string()) fail("'extensionsRequired' must hold strings");
      const std::string name = e.get<std::string>();
      bool known = false;
      for (const char* s : kGltfExtensions) known = known || name == s;
      if (!known) fail("requires extension " + name + ", which penumbra does not support");
    }
  }

  // Returns the decoded size of a data: URI, failing on an unknown header or bad base64.
  std::uint64_t dataUriSize(const std::string& uri, const std::string& what) const {
    for (const char* header : kDataUriHeaders) {
      const std::size_t n = std::strlen(header);
      if (uri.compare(0, n, header) != 0) continue;
      const long long size = base64DecodedSize(uri, n);
      if (size <= 0) fail(what + ": data URI is not valid base64");
      return std::uint64_t(size);
    }
    fail(what + ": unsupported data URI '" + uri.substr(0, std::min<std::size_t>(40, uri.find(','))) +
         "' (base64 octet-stream, gltf-buffer or image only)");
  }

  // The file an external URI names, after the sandbox rules; empty if it does not exist.
  std::string externalFile(const std::string& uri, const std::string& what) const {
    const std::string decoded = urlDecode(uri);
    if (std::string why = relativePathProblem(decoded); !why.empty()) {
      fail(what + ": uri '" + uri + "' " + why + " (only files next to the glTF file, no network, no '..')");
    }
    const std::string file = (fs::path(folder) / decoded).lexically_normal().string();
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return {};
    if (!isInsideFolder(file, folder)) fail(what + ": uri '" + uri + "' resolves outside " + folder);
    return file;
  }

  std::vector<std::uint64_t> checkBuffers() const {
    std::vector<std::uint64_t> sizes;
    const Json* buffers = arrayOf("buffers");
    if (!buffers) return sizes;
    for (std::size_t i = 0; i < buffers->size(); ++i) {
      const Json& b = (*buffers)[i];
      const std::string what = "buffer " + std::to_string(i);
      std::uint64_t length = 0;
      if (!unsignedField(b, "byteLength", length) || length == 0 || length > kMaxFileBytes) {
        fail(what + ": 'byteLength' missing or not a positive integer below 1 GiB");
      }
      const auto uri = b.find("uri");
      if (uri == b.end() && isMeshoptFallbackBuffer(b)) {
        // No data: the bufferViews in it are decoded from EXT_meshopt_compression streams.
      } else if (uri == b.end()) {
        if (!glb || i != 0) fail(what + " has no 'uri'");
        if (binChunkBytes == 0) fail(what + " has no 'uri' but the GLB has no BIN chunk");
        if (length > binChunkBytes) {
          fail(what + " declares " + std::to_string(length) + " bytes but the GLB BIN chunk has " +
               std::to_string(binChunkBytes));
        }
      } else if (!uri->is_string()) {
        fail(what + ": 'uri' must be a string");
      } else if (uri->get<std::string>().rfind("data:", 0) == 0) {
        const std::uint64_t size = dataUriSize(uri->get<std::string>(), what);
        if (size != length) {
          fail(what + " declares " + std::to_string(length) + " bytes but its data URI holds " + std::to_string(size));
        }
      } else {
        const std::string file = externalFile(uri->get<std::string>(), what);
        if (file.empty()) fail(what + ": '" + uri->get<std::string>() + "' not found in " + folder);
        std::error_code ec;
        const std::uint64_t size = fs::file_size(file, ec);
        if (ec || size != length) {
          fail(what + " declares " + std::to_string(length) + " bytes but '" + uri->get<std::string>() + "' has " +
               std::to_string(size));
        }
      }
      sizes.push_back(length);
    }
    return sizes;
  }

  void checkBufferViews(const std::vector<std::uint64_t>& bufferSizes) const {
    const Json* views = arrayOf("bufferViews");
    if (!views) return;
    for (std::size_t i = 0; i < views->size(); ++i) {
      const Json& v = (*views)[i];
      const std::string what = "bufferView " + std::to_string(i);
      std::uint64_t buffer = 0, offset = 0, length = 0, stride = 0;
      if (!unsignedField(v, "buffer", buffer) || buffer >= bufferSizes.size()) {
        fail(what + ": 'buffer' missing or out of range");
      }
      unsignedField(v, "byteOffset", offset);
      if (!unsignedField(v, "byteLength", length) || length == 0) {
        fail(what + ": 'byteLength' missing or not a positive integer");
      }
      const std::uint64_t size = bufferSizes[buffer];
      if (offset > size || length > size - offset) {
        fail(what + " (offset " + std::to_string(offset) + ", length " + std::to_string(length) + ") overruns buffer " +
             std::to_string(buffer) + " (" + std::to_string(size) + " bytes)");
      }
      if (unsignedField(v, "byteStride", stride) && (stride < 4 || stride > 252 || stride % 4)) {
        fail(what + ": 'byteStride' must be a multiple of 4 in [4, 252]");
      }
    }
  }

  void checkImages() const {
    const Json* images = arrayOf("images");
    if (!images) return;
    const Json* views = arrayOf("bufferViews");
    for (std::size_t i = 0; i < images->size(); ++i) {
      const Json& img = (*images)[i];
      const std::string what = "image " + std::to_string(i);
      const auto uri = img.find("uri");
      std::uint64_t view = 0;
      if (uri != img.end()) {
        if (!uri->is_string()) fail(what + ": 'uri' must be a string");
        const std::string u = uri->get<std::string>();
        if (u.rfind("data:", 0) == 0) {
          dataUriSize(u, what);
        } else if (externalFile(u, what).empty()) {
          warnings.push_back(path + ": " + what + ": '" + u + "' not found; texture ignored");
        }
      } else if (unsignedField(img, "bufferView", view)) {
        if (!views || view >= views->size()) fail(what + ": 'bufferView' out of range");
      }
    }
  }

  // The JSON types of the properties penumbra reads, as the glTF 2.0 schema gives them. tinygltf
  // ignores a property of the wrong type without a word (a node's "mesh": "0" dropped the mesh,
  // a two-number translation was no translation, "children": "1" no children) or fails with a
  // message that does not say where: both become one error naming the object and the property.
  enum class Kind { Index, Number, Boolean, String, Object, Indices, Numbers };
  struct Property {
    const char* key;
    Kind kind;
    std::size_t count = 0;  // Numbers: the length the schema fixes (0: any)
  };
  void checkProperties(const Json& object, const std::string& what, std::initializer_list<Property> properties) const {
    for (const Property& p : properties) {
      const auto it = object.find(p.key);
      if (it == object.end()) continue;
      const Json& v = *it;
      auto index = [](const Json& x) {
        return x.is_number_unsigned() || (x.is_number_integer() && x.get<long long>() >= 0);
      };
      bool ok = false;
      std::string expected;
      switch (p.kind) {
        case Kind::Index:
          ok = index(v), expected = "a non-negative integer";
          break;
        case Kind::Number:
          ok = v.is_number(), expected = "a number";
          break;
        case Kind::Boolean:
          ok = v.is_boolean(), expected = "true or false";
          break;
        case Kind::String:
          ok = v.is_string(), expected = "a string";
          break;
        case Kind::Object:
          ok = v.is_object(), expected = "an object";
          break;
        case Kind::Indices:
          ok = v.is_array() && std::all_of(v.begin(), v.end(), index), expected = "an array of non-negative integers";
          break;
        case Kind::Numbers:
          ok = v.is_array() && (p.count == 0 || v.size() == p.count) &&
               std::all_of(v.begin(), v.end(), [](const Json& x) { return x.is_number(); });
          expected = p.count ? std::to_string(p.count) + " numbers" : "an array of numbers";
          break;
      }
      if (!ok) fail(what + ": '" + p.key + "' must be " + expected + ", got " + shownJson(v));
    }
  }

  void checkTypes() const {
    using K = Kind;
    auto each = [&](const char* key, std::initializer_list<Property> properties) {
      if (const Json* items = arrayOf(key))
        for (std::size_t i = 0; i < items->size(); ++i)
          checkProperties((*items)[i], std::string(key) + "[" + std::to_string(i) + "]", properties);
    };
    each("accessors", {{"bufferView", K::Index},
                       {"byteOffset", K::Index},
                       {"componentType", K::Index},
                       {"normalized", K::Boolean},
                       {"count", K::Index},
                       {"type", K::String},
                       {"max", K::Numbers},
                       {"min", K::Numbers},
                       {"sparse", K::Object},
                       {"name", K::String}});
    each("bufferViews", {{"buffer", K::Index},
                         {"byteOffset", K::Index},
                         {"byteLength", K::Index},
                         {"byteStride", K::Index},
                         {"target", K::Index},
                         {"name", K::String}});
    each("buffers", {{"uri", K::String}, {"byteLength", K::Index}, {"name", K::String}});
    each("images", {{"uri", K::String}, {"mimeType", K::String}, {"bufferView", K::Index}, {"name", K::String}});
    each("textures", {{"sampler", K::Index}, {"source", K::Index}, {"name", K::String}});
    each("samplers", {{"magFilter", K::Index}, {"minFilter", K::Index}, {"wrapS", K::Index}, {"wrapT", K::Index}});
    each("nodes", {{"camera", K::Index},
                   {"children", K::Indices},
                   {"skin", K::Index},
                   {"matrix", K::Numbers, 16},
                   {"mesh", K::Index},
                   {"rotation", K::Numbers, 4},
                   {"scale", K::Numbers, 3},
                   {"translation", K::Numbers, 3},
                   {"weights", K::Numbers},
                   {"name", K::String},
                   {"extensions", K::Object}});
    each("scenes", {{"nodes", K::Indices}, {"name", K::String}});
    each("materials", {{"name", K::String}, {"extensions", K::Object}});
    if (const Json* meshes = arrayOf("meshes")) {
      for (std::size_t i = 0; i < meshes->size(); ++i) {
        const std::string mesh = "meshes[" + std::to_string(i) + "]";
        checkProperties((*meshes)[i], mesh, {{"weights", K::Numbers}, {"name", K::String}});
        const Json& primitives = (*meshes)[i]["primitives"];  // an array: checkTopLevel
        for (std::size_t k = 0; k < primitives.size(); ++k) {
          const std::string what = mesh + ".primitives[" + std::to_string(k) + "]";
          if (!primitives[k].is_object()) fail(what + " must be an object, got " + shownJson(primitives[k]));
          checkProperties(primitives[k], what,
                          {{"attributes", K::Object},
                           {"indices", K::Index},
                           {"material", K::Index},
                           {"mode", K::Index},
                           {"extensions", K::Object}});
          if (const auto a = primitives[k].find("attributes"); a != primitives[k].end())
            for (const auto& [name, value] : a->items())
              checkProperties(*a, what + ".attributes", {{name.c_str(), K::Index}});
        }
      }
    }
  }

  // Materials as the specification types them: tinygltf drops a pbrMetallicRoughness, texture
  // reference or factor of the wrong JSON type without a word (a string `index` left the
  // material untextured, a pbr block given as an array shaded it white), so they are refused here.
  void checkMaterials() const {
    const Json* materials = arrayOf("materials");
    if (!materials) return;
    for (std::size_t i = 0; i < materials->size(); ++i) {
      const Json& m = (*materials)[i];
      const std::string what = "materials[" + std::to_string(i) + "]";
      auto numbers = [&](const Json& o, const char* key, std::size_t count, const std::string& at) {
        const auto it = o.find(key);
        if (it == o.end()) return;
        bool ok = count == 1 ? it->is_number() : it->is_array() && it->size() == count;
        if (it->is_array())
          for (const Json& x : *it) ok = ok && x.is_number();
        if (!ok)
          fail(at + "'" + key + "' must be " +
               (count == 1 ? std::string("a number") : std::to_string(count) + " numbers") + ", got " + shownJson(*it));
      };
      auto textureInfo = [&](const Json& o, const char* key, const std::string& at) {
        const auto it = o.find(key);
        if (it == o.end()) return;
        const std::string here = at + "'" + key + "'";
        if (!it->is_object()) fail(here + " must be an object, got " + shownJson(*it));
        std::uint64_t index = 0, texCoord = 0;
        if (!unsignedField(*it, "index", index)) fail(here + " has no 'index'");
        if (index == std::numeric_limits<std::uint64_t>::max())
          fail(here + ": 'index' must be a non-negative integer, got " + shownJson(it->at("index")));
        if (unsignedField(*it, "texCoord", texCoord) && texCoord == std::numeric_limits<std::uint64_t>::max())
          fail(here + ": 'texCoord' must be a non-negative integer, got " + shownJson(it->at("texCoord")));
        numbers(*it, "scale", 1, here + ": ");
        numbers(*it, "strength", 1, here + ": ");
      };
      const std::string at = what + ": ";
      if (const auto pbr = m.find("pbrMetallicRoughness"); pbr != m.end()) {
        if (!pbr->is_object()) fail(at + "'pbrMetallicRoughness' must be an object, got " + shownJson(*pbr));
        const std::string in = at + "pbrMetallicRoughness: ";
        numbers(*pbr, "baseColorFactor", 4, in);
        numbers(*pbr, "metallicFactor", 1, in);
        numbers(*pbr, "roughnessFactor", 1, in);
        textureInfo(*pbr, "baseColorTexture", in);
        textureInfo(*pbr, "metallicRoughnessTexture", in);
      }
      for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"}) textureInfo(m, key, at);
      numbers(m, "emissiveFactor", 3, at);
      numbers(m, "alphaCutoff", 1, at);
      if (const auto mode = m.find("alphaMode"); mode != m.end() && !mode->is_string())
        fail(at + "'alphaMode' must be a string, got " + shownJson(*mode));
      if (const auto sided = m.find("doubleSided"); sided != m.end() && !sided->is_boolean())
        fail(at + "'doubleSided' must be true or false, got " + shownJson(*sided));
    }
  }

  void checkTopLevel() const {
    for (const char* key : {"accessors", "animations", "cameras", "materials", "meshes", "nodes", "samplers", "scenes",
                            "skins", "textures"}) {
      arrayOf(key);
    }
    if (const auto it = doc.find("scene"); it != doc.end() && !it->is_number_unsigned()) {
      fail("'scene' must be a non-negative integer");
    }
    if (const Json* meshes = arrayOf("meshes")) {
      for (std::size_t i = 0; i < meshes->size(); ++i) {
        const auto p = (*meshes)[i].find("primitives");
        if (p == (*meshes)[i].end() || !p->is_array()) {
          fail("mesh " + std::to_string(i) + ": 'primitives' must be an array");
        }
      }
    }
  }
};

// Returns the JSON chunk of a GLB after checking the container; sets binBytes (0: none).
std::string checkGlb(const std::string& path, std::vector<unsigned char>& bytes, std::uint64_t& binBytes,
                     std::vector<std::string>& warnings) {
  const std::uint64_t size = bytes.size();
  if (size < 20) throw Error(path, "truncated GLB: " + std::to_string(size) + " bytes");
  if (readU32(bytes.data()) != kGlbMagic) throw Error(path, "not a GLB file (bad magic)");
  const std::uint32_t version = readU32(&bytes[4]);
  if (version != 2) throw Error(path, "GLB version " + std::to_string(version) + " (expected 2)");
  const std::uint64_t length = readU32(&bytes[8]);
  if (length > size) {
    throw Error(path,
                "GLB header declares " + std::to_string(length) + " bytes but the file has " + std::to_string(size));
  }
  if (length < size) {
    warnings.push_back(path + ": " + std::to_string(size - length) + " bytes after the GLB's declared length ignored");
  }
  const std::uint64_t jsonLength = readU32(&bytes[12]);
  if (readU32(&bytes[16]) != kChunkJson) throw Error(path, "first GLB chunk is not JSON");
  if (jsonLength == 0 || 20 + jsonLength > length) {
    throw Error(path, "GLB JSON chunk length " + std::to_string(jsonLength) + " does not fit in the file (" +
                          std::to_string(length) + " bytes)");
  }
  const std::uint64_t binStart = 20 + jsonLength;
  binBytes = 0;
  if (binStart < length) {
    if (binStart % 4 != 0) throw Error(path, "GLB JSON chunk is not padded to 4 bytes");
    if (length - binStart < 8) throw Error(path, "truncated GLB chunk header after the JSON");
    const std::uint64_t binLength = readU32(&bytes[binStart]);
    if (readU32(&bytes[binStart + 4]) != kChunkBin) {
      throw Error(path, "second GLB chunk is not BIN");
    }
    if (binLength > length - binStart - 8) {
      throw Error(path, "GLB BIN chunk length " + std::to_string(binLength) + " exceeds the file (" +
                            std::to_string(length - binStart - 8) + " bytes left)");
    }
    if (binLength == 0 || binLength % 4 != 0) {
      throw Error(path, "GLB BIN chunk length " + std::to_string(binLength) + " is not a positive multiple of 4");
    }
    binBytes = binLength;
  }
  // The spec pads with spaces; some exporters pad with NULs, which JSON parsers (ours and
  // tinygltf's, which reads the same bytes) refuse.
  for (std::uint64_t i = binStart; i > 20 && bytes[i - 1] == 0; --i) bytes[i - 1] = ' ';
  return std::string(bytes.begin() + 20, bytes.begin() + std::ptrdiff_t(binStart));
}

// Stubs in `doc` what tinygltf would refuse in a compressed file (see parseGltfSandboxed); the
// accessors given a bufferView go to `dracoIndices`. Returns whether anything changed. `doc`
// has passed the checks above (buffers, meshes and primitives are objects where present).
bool stubForTinygltf(Json& doc, std::vector<std::size_t>& dracoIndices) {
  bool changed = false;
  if (auto buffers = doc.find("buffers"); buffers != doc.end() && buffers->is_array()) {
    for (Json& b : *buffers) {
      if (!b.is_object() || b.contains("uri") || !isMeshoptFallbackBuffer(b)) continue;
      b["uri"] = "data:application/octet-stream;base64,AAAAAA==";
      b["byteLength"] = 4;
      changed = true;
    }
  }
  auto accessors = doc.find("accessors");
  auto meshes = doc.find("meshes");
  if (accessors == doc.end() || !accessors->is_array() || meshes == doc.end() || !meshes->is_array()) return changed;
  for (const Json& mesh : *meshes) {
    const auto primitives = mesh.find("primitives");
    if (!mesh.is_object() || primitives == mesh.end() || !primitives->is_array()) continue;
    for (const Json& p : *primitives) {
      if (!p.is_object()) continue;
      const auto ext = p.find("extensions");
      const auto indices = p.find("indices");
      if (ext == p.end() || !ext->is_object() || indices == p.end() || !indices->is_number_unsigned()) continue;
      const auto draco = ext->find("KHR_draco_mesh_compression");
      if (draco == ext->end() || !draco->is_object()) continue;
      const auto view = draco->find("bufferView");
      const std::size_t a = indices->get<std::size_t>();
      if (view == draco->end() || !view->is_number_unsigned() || a >= accessors->size()) continue;
      Json& accessor = (*accessors)[a];
      if (!accessor.is_object() || accessor.contains("bufferView")) continue;
      accessor["bufferView"] = *view;
      dracoIndices.push_back(a);
      changed = true;
    }
  }
  return changed;
}

// The GLB `bytes` (JSON chunk of `jsonBytes`) with its JSON chunk replaced by `json`, padded with
// spaces to 4 bytes; the BIN chunk after it unchanged.
std::vector<unsigned char> withJsonChunk(const std::vector<unsigned char>& bytes, std::size_t jsonBytes,
                                         std::string json) {
  json.resize((json.size() + 3) / 4 * 4, ' ');
  std::vector<unsigned char> out(bytes.begin(), bytes.begin() + 12);
  auto put = [&](std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
  };
  put(std::uint32_t(json.size()));
  put(kChunkJson);
  out.insert(out.end(), json.begin(), json.end());
  out.insert(out.end(), bytes.begin() + std::ptrdiff_t(20 + jsonBytes), bytes.end());
  const std::uint32_t total = std::uint32_t(out.size());
  for (int i = 0; i < 4; ++i) out[8 + std::size_t(i)] = static_cast<unsigned char>(total >> (8 * i));
  return out;
}

std::string firstLines(const std::string& text) {
  std::string out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    out += (out.empty() ? "" : "; ") + line;
    if (out.size() > 300) break;
  }
  return out;
}

}  // namespace

void parseGltfSandboxed(const std::string& path, tinygltf::Model& model, Json& json,
                        std::vector<std::string>& warnings) {
  std::vector<unsigned char> bytes = readBinary(path);
  const bool glb = bytes.size() >= 4 && readU32(bytes.data()) == kGlbMagic;
  if (!glb && lowerExtension(path) == ".glb") throw Error(path, "not a GLB file (bad magic)");
  std::uint64_t binBytes = 0;
  const std::string text = glb ? checkGlb(path, bytes, binBytes, warnings) : std::string(bytes.begin(), bytes.end());

  json = parseJsonDocument(text, path, "glTF");  // refuses repeated keys, which tinygltf would drop
  if (!json.is_object()) throw Error(path, "the glTF JSON is not an object");
  std::error_code ec;
  const fs::path parent = fs::path(path).parent_path();
  const std::string folder = fs::absolute(parent.empty() ? fs::path(".") : parent, ec).lexically_normal().string();
  Checker check{path, folder, json, warnings, binBytes, glb};
  try {
    check.checkVersion();
    check.checkExtensions();
    check.checkTopLevel();
    check.checkTypes();
    check.checkBufferViews(check.checkBuffers());
    check.checkImages();
    check.checkMaterials();
  } catch (const Json::exception& e) {
    throw Error(path, std::string("malformed glTF: ") + e.what());
  }

  // What tinygltf 2.7 refuses in a compressed file is stubbed in the JSON it is given (the
  // loader reads the real thing): an EXT_meshopt_compression fallback buffer (no uri, no data)
  // becomes 4 zero bytes; the indices accessor of a KHR_draco_mesh_compression primitive (no
  // bufferView) points at the Draco stream's bufferView, and is set back to none after parsing.
  std::string given = text;
  std::vector<std::size_t> dracoIndices;
  if (Json stubbed = json; stubForTinygltf(stubbed, dracoIndices)) {
    given = stubbed.dump();
    if (glb) bytes = withJsonChunk(bytes, text.size(), given);
  }

  Sandbox sandbox{folder};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&sandboxFileExists, &sandboxExpand, &sandboxRead, &sandboxWrite, &sandbox});
  loader.SetImageLoader(&keepEncoded, nullptr);
  std::string err, warn;
  bool ok = false;
  if (glb) {
    ok =
        loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), folder);
  } else {
    ok = loader.LoadASCIIFromString(&model, &err, &warn, given.data(), static_cast<unsigned int>(given.size()), folder);
  }
  if (!ok) throw Error(path, "tinygltf: " + (err.empty() ? std::string("load failed") : firstLines(err)));
  for (std::size_t a : dracoIndices)
    if (a < model.accessors.size()) model.accessors[a].bufferView = -1;
  if (!warn.empty()) warnings.push_back(path + ": tinygltf: " + firstLines(warn));
}

bool encodedImageSize(const std::vector<unsigned char>& encoded, int& width, int& height, std::string& why) {
  long long w = -1, h = -1;
  const auto* b = encoded.data();
  const std::size_t n = encoded.size();
  if (PngIhdr ihdr; readPngIhdr(b, n, ihdr)) {
    w = ihdr.width, h = ihdr.height;
    if (w > 0 && h > 0) why = pngSizeProblem(w, h, ihdr.bitDepth, ihdr.colourType, n);
    if (!why.empty()) return false;
  } else if (n >= 4 && b[0] == 0xFF && b[1] == 0xD8) {
    for (std::size_t i = 2; i + 9 < n;) {
      if (b[i] != 0xFF) {
        ++i;
        continue;
      }
      const unsigned char marker = b[i + 1];
      const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
      if (sof) {
        h = b[i + 5] << 8 | b[i + 6];
        w = b[i + 7] << 8 | b[i + 8];
        break;
      }
      if (marker == 0xD8 || marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0xFF) {
        i += marker == 0xFF ? 1 : 2;
        continue;
      }
      i += 2 + (std::size_t(b[i + 2]) << 8 | b[i + 3]);
    }
  } else {
    why = "not a PNG or JPEG image";
    return false;
  }
  if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide) {
    why = "image size " + std::to_string(w) + "x" + std::to_string(h) + " unreadable or above " +
          std::to_string(kMaxImageSide) + "^2";
    return false;
  }
  width = int(w);
  height = int(h);
  return true;
}

double decodeBytes(int width, int height) {
  return double(width) * double(height) * 24.0;  // stb's samples (at most 8 bytes) + float RGBA
}

bool decodeGltfImage(const std::vector<unsigned char>& encoded, Image& out, std::string& why, bool srgb) {
  // Sides from the header first, so a tiny file cannot make stb allocate gigabytes.
  int w = 0, h = 0;
  if (!encodedImageSize(encoded, w, h, why)) return false;
  const auto* b = encoded.data();
  const std::size_t n = encoded.size();
  tinygltf::Image decoded;
  std::string err, warn;
  if (!tinygltf::LoadImageData(&decoded, 0, &err, &warn, 0, 0, b, int(n), nullptr) || decoded.width <= 0 ||
      decoded.height <= 0 || decoded.component < 1 || decoded.component > 4) {
    why = "cannot decode: " + firstLines(err);
    return false;
  }
  const int bytesPer = decoded.bits == 16 ? 2 : 1;
  const std::size_t texels = std::size_t(decoded.width) * std::size_t(decoded.height);
  if (decoded.image.size() < texels * std::size_t(decoded.component * bytesPer)) {
    why = "decoder returned too little data";
    return false;
  }
  out = Image(decoded.width, decoded.height, 4, 1.0f);
  const float scale = bytesPer == 2 ? 1.0f / 65535.0f : 1.0f / 255.0f;
  for (std::size_t t = 0; t < texels; ++t) {
    float v[4] = {0, 0, 0, 1};
    for (int c = 0; c < decoded.component; ++c) {
      const std::size_t at = (t * std::size_t(decoded.component) + std::size_t(c)) * bytesPer;
      unsigned raw = decoded.image[at];
      if (bytesPer == 2) {  // stb returns 16-bit samples in host order
        std::uint16_t sample;
        std::memcpy(&sample, &decoded.image[at], 2);
        raw = sample;
      }
      v[c] = float(raw) * scale;
    }
    if (decoded.component <= 2) {  // grey (+ alpha)
      v[3] = decoded.component == 2 ? v[1] : 1.0f;
      v[1] = v[2] = v[0];
    }
    for (int c = 0; c < 3; ++c) out.data[t * 4 + std::size_t(c)] = srgb ? srgbToLinear(v[c]) : v[c];
    out.data[t * 4 + 3] = v[3];
  }
  return true;
}

}  // namespace penumbra::detail
