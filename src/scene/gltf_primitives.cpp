// glTF primitives to triangle meshes: every accessor checked against its bufferView before a
// byte is read (gltf_validate.cpp has checked the buffers and bufferViews), KHR_mesh_quantization's
// integer attributes, EXT_meshopt_compression's decoded bufferViews and KHR_draco_mesh_compression's
// streams (gltf_compression.h), strips and fans to triangles.
#include <algorithm>
#include <cstring>

#include "scene/gltf_compression.h"
#include "scene/gltf_loader.h"

namespace penumbra::detail {

namespace {

// A checked view of an accessor's elements: element i starts at data + i * stride.
struct AccessorView {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
  int componentType = 0;
  int components = 0;
  bool normalized = false;
};

int componentBytes(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

int typeComponents(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

// Thrown for a primitive that is skipped with a warning rather than failing the file.
struct SkipPrimitive {
  std::string why;
};

// Whether buffer `index` is an EXT_meshopt_compression fallback buffer (its data a stub).
bool isFallback(const Loader& L, int index) {
  const auto buffers = L.json.find("buffers");
  return buffers != L.json.end() && buffers->is_array() && std::size_t(index) < buffers->size() &&
         isMeshoptFallbackBuffer((*buffers)[std::size_t(index)]);
}

// Checks accessor `index` (used as `role`) and returns a view of it. `types` lists the allowed
// (type, componentType) pairs. Layout faults throw Error; unsupported-but-valid layouts skip.
AccessorView viewAccessor(const Loader& L, int index, const std::string& role,
                          std::initializer_list<std::pair<int, int>> types) {
  const std::string what = "accessor " + std::to_string(index) + " (" + role + ")";
  if (index < 0 || std::size_t(index) >= L.gltf.accessors.size()) {
    L.fail(role + " refers to accessor " + std::to_string(index) + ", which does not exist");
  }
  const tinygltf::Accessor& a = L.gltf.accessors[std::size_t(index)];
  bool typeOk = false;
  for (const auto& [type, component] : types) typeOk = typeOk || (a.type == type && a.componentType == component);
  if (!typeOk) {
    L.fail(what + ": unsupported type/componentType " + std::to_string(a.type) + "/" + std::to_string(a.componentType));
  }
  if (a.count == 0) L.fail(what + ": count is 0");
  if (a.sparse.isSparse) throw SkipPrimitive{what + " is sparse (not supported)"};
  if (a.bufferView < 0) throw SkipPrimitive{what + " has no bufferView (all zeros)"};
  if (std::size_t(a.bufferView) >= L.gltf.bufferViews.size()) {
    L.fail(what + ": bufferView " + std::to_string(a.bufferView) + " does not exist");
  }
  const tinygltf::BufferView& v = L.gltf.bufferViews[std::size_t(a.bufferView)];
  if (v.buffer < 0 || std::size_t(v.buffer) >= L.gltf.buffers.size()) {
    L.fail(what + ": buffer " + std::to_string(v.buffer) + " does not exist");
  }
  // A bufferView compressed with EXT_meshopt_compression reads from its decoded bytes.
  const auto decoded = L.decodedViews.find(a.bufferView);
  const unsigned char* bytes = nullptr;
  if (decoded != L.decodedViews.end()) {
    bytes = decoded->second.data();
  } else {
    const std::vector<unsigned char>& data = L.gltf.buffers[std::size_t(v.buffer)].data;
    if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset) {
      L.fail("bufferView " + std::to_string(a.bufferView) + " overruns buffer " + std::to_string(v.buffer) +
             (isFallback(L, v.buffer) ? " (an EXT_meshopt_compression fallback buffer, without data)" : ""));
    }
    bytes = data.data() + v.byteOffset;
  }
  const std::size_t component = std::size_t(componentBytes(a.componentType));
  const std::size_t element = component * std::size_t(typeComponents(a.type));
  const std::size_t stride = v.byteStride ? v.byteStride : element;
  if (stride < element) {
    L.fail(what + ": byteStride " + std::to_string(stride) + " is smaller than an element (" + std::to_string(element) +
           " bytes)");
  }
  if ((v.byteOffset + a.byteOffset) % component != 0 || stride % component != 0) {
    L.fail(what + ": offset " + std::to_string(v.byteOffset + a.byteOffset) + " or stride " + std::to_string(stride) +
           " is not a multiple of the component size " + std::to_string(component));
  }
  // The last element ends at offset + stride * (count - 1) + element: the stride's padding
  // after the last element need not be there.
  const std::size_t available = v.byteLength;
  if (a.byteOffset > available || element > available - a.byteOffset ||
      a.count - 1 > (available - a.byteOffset - element) / stride) {
    const long double needed = (long double)a.byteOffset + (long double)stride * (long double)(a.count - 1) + element;
    L.fail(what + ": needs " + std::to_string((unsigned long long)needed) + " bytes (offset " +
           std::to_string(a.byteOffset) + ", stride " + std::to_string(stride) + ", count " + std::to_string(a.count) +
           ") but bufferView " + std::to_string(a.bufferView) + " has " + std::to_string(v.byteLength));
  }
  AccessorView out;
  out.data = bytes + a.byteOffset;
  out.stride = stride;
  out.count = a.count;
  out.componentType = a.componentType;
  out.components = typeComponents(a.type);
  out.normalized = a.normalized;
  return out;
}

// Component c of element i as a float: normalized integers to [0, 1] or [-1, 1] (glTF 2.0
// section 3.11), others as their value (KHR_mesh_quantization's unnormalized attributes).
float readComponent(const AccessorView& a, std::size_t i, int c) {
  const unsigned char* p = a.data + i * a.stride;
  switch (a.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p + 4 * c, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float v = float(std::int8_t(p[c]));
      return a.normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return a.normalized ? float(p[c]) / 255.0f : float(p[c]);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t u;
      std::memcpy(&u, p + 2 * c, 2);
      return a.normalized ? std::max(float(u) / 32767.0f, -1.0f) : float(u);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t u;
      std::memcpy(&u, p + 2 * c, 2);
      return a.normalized ? float(u) / 65535.0f : float(u);
    }
    default:
      return 0.0f;
  }
}

std::uint32_t readIndex(const AccessorView& a, std::size_t i) {
  const unsigned char* p = a.data + i * a.stride;
  switch (a.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t u;
      std::memcpy(&u, p, 2);
      return u;
    }
    default: {
      std::uint32_t u;
      std::memcpy(&u, p, 4);
      return u;
    }
  }
}

// The accessor types an attribute may have: glTF 2.0's, and with KHR_mesh_quantization its
// integer forms (the extension's table: positions any 8/16-bit integer, normals normalized
// signed ones, texture coordinates any 8/16-bit integer).
std::initializer_list<std::pair<int, int>> attributeTypes(const Loader& L, const std::string& semantic) {
  using P = std::pair<int, int>;
  static const std::initializer_list<P> kPosition = {{TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT}};
  static const std::initializer_list<P> kPositionQ = {{TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT},
                                                      {TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_BYTE},
                                                      {TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE},
                                                      {TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_SHORT},
                                                      {TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}};
  static const std::initializer_list<P> kNormalQ = {{TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT},
                                                    {TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_BYTE},
                                                    {TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_SHORT}};
  static const std::initializer_list<P> kUv = {{TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_FLOAT},
                                               {TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE},
                                               {TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}};
  static const std::initializer_list<P> kUvQ = {{TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_FLOAT},
                                                {TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_BYTE},
                                                {TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE},
                                                {TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_SHORT},
                                                {TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}};
  if (semantic == "POSITION") return L.quantized ? kPositionQ : kPosition;
  if (semantic == "NORMAL") return L.quantized ? kNormalQ : kPosition;
  return L.quantized ? kUvQ : kUv;
}

// Checks accessor `index` of attribute `semantic` and returns its view, normalization settled:
// integer normals must be normalized; glTF 2.0's integer texture coordinates are normalized
// whatever the flag says (only KHR_mesh_quantization has unnormalized ones).
AccessorView viewAttribute(const Loader& L, int index, const std::string& name, const std::string& semantic) {
  AccessorView v = viewAccessor(L, index, name + " " + semantic, attributeTypes(L, semantic));
  if (v.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return v;
  if (semantic == "NORMAL" && !v.normalized) L.fail(name + " NORMAL: integer normals must be normalized");
  if (semantic == "TEXCOORD_0" && !L.quantized) v.normalized = true;
  return v;
}

// NORMAL and TEXCOORD_0 from their accessors (each when `normals` / `uvs`), for `vertices`
// vertices; an accessor of another count is ignored with a warning.
void readShadingAttributes(Loader& L, const tinygltf::Primitive& p, const std::string& name, std::size_t vertices,
                           geo::TriangleMesh& m, bool normals, bool uvs) {
  if (const auto it = p.attributes.find("NORMAL"); normals && it != p.attributes.end()) {
    const AccessorView nrm = viewAttribute(L, it->second, name, "NORMAL");
    if (nrm.count != vertices) {
      L.warn(name + ": NORMAL count differs from POSITION; normals ignored");
    } else {
      m.normals.resize(nrm.count);
      for (std::size_t i = 0; i < nrm.count; ++i) {
        for (int c = 0; c < 3; ++c) m.normals[i][c] = readComponent(nrm, i, c);
      }
    }
  }
  if (const auto it = p.attributes.find("TEXCOORD_0"); uvs && it != p.attributes.end()) {
    const AccessorView uv = viewAttribute(L, it->second, name, "TEXCOORD_0");
    if (uv.count != vertices) {
      L.warn(name + ": TEXCOORD_0 count differs from POSITION; texture coordinates ignored");
    } else {
      m.uvs.resize(uv.count);
      for (std::size_t i = 0; i < uv.count; ++i) {
        m.uvs[i] = {readComponent(uv, i, 0), readComponent(uv, i, 1)};
      }
    }
  }
}

// Vertex count and index list of a primitive read from its accessors (`position`: POSITION's).
std::size_t readAccessors(Loader& L, const tinygltf::Primitive& p, int position, const std::string& name,
                          geo::TriangleMesh& m, std::vector<std::uint32_t>& indices) {
  const AccessorView pos = viewAttribute(L, position, name, "POSITION");
  m.positions.resize(pos.count);
  for (std::size_t i = 0; i < pos.count; ++i) {
    for (int c = 0; c < 3; ++c) m.positions[i][c] = readComponent(pos, i, c);
  }
  readShadingAttributes(L, p, name, pos.count, m, true, true);
  if (p.indices >= 0) {
    const AccessorView idx = viewAccessor(L, p.indices, name + " indices",
                                          {{TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE},
                                           {TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                           {TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}});
    indices.resize(idx.count);
    for (std::size_t i = 0; i < idx.count; ++i) indices[i] = readIndex(idx, i);
  } else {
    indices.resize(pos.count);
    for (std::size_t i = 0; i < pos.count; ++i) indices[i] = std::uint32_t(i);
  }
  return pos.count;
}

// The same from the primitive's Draco stream; NORMAL or TEXCOORD_0 outside the stream is read
// from its accessor (the extension lets a primitive compress only some attributes).
std::size_t readDraco(Loader& L, const tinygltf::Primitive& p, const std::string& name, geo::TriangleMesh& m,
                      std::vector<std::uint32_t>& indices) {
  DracoPrimitive d = decodeDraco(L.path, L.gltf, p, name);
  const std::size_t n = d.vertices;
  m.positions.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    m.positions[i] = {d.positions[3 * i], d.positions[3 * i + 1], d.positions[3 * i + 2]};
  if (!d.normals.empty()) {
    m.normals.resize(n);
    for (std::size_t i = 0; i < n; ++i) m.normals[i] = {d.normals[3 * i], d.normals[3 * i + 1], d.normals[3 * i + 2]};
  }
  if (!d.uvs.empty()) {
    m.uvs.resize(n);
    for (std::size_t i = 0; i < n; ++i) m.uvs[i] = {d.uvs[2 * i], d.uvs[2 * i + 1]};
  }
  readShadingAttributes(L, p, name, n, m, d.normals.empty(), d.uvs.empty());
  indices = std::move(d.indices);
  return n;
}

}  // namespace

Primitive convertPrimitive(Loader& L, const tinygltf::Primitive& p, const std::string& name) {
  Primitive out;
  const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  if (mode > TINYGLTF_MODE_TRIANGLE_FAN) L.fail(name + ": unknown primitive mode " + std::to_string(mode));
  if (mode < TINYGLTF_MODE_TRIANGLES) {
    static const char* kNames[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
    L.warn(name + ": " + kNames[mode] + " primitive ignored (casts no shadow)");
    ++L.primitivesSkipped;
    out.skipped = true;
    return out;
  }
  if (p.material >= 0 && std::size_t(p.material) >= L.gltf.materials.size()) {
    L.fail(name + ": material " + std::to_string(p.material) + " does not exist");
  }
  out.material = p.material;
  if (!p.targets.empty()) L.warn(name + ": morph targets ignored (base shape used)");
  const auto position = p.attributes.find("POSITION");
  if (position == p.attributes.end()) {
    L.warn(name + ": no POSITION attribute; primitive dropped");
    ++L.primitivesSkipped;
    out.skipped = true;
    return out;
  }
  try {
    geo::TriangleMesh& m = out.mesh;
    std::vector<std::uint32_t> indices;
    std::size_t vertices = 0;
    if (hasDraco(p)) {
      vertices = readDraco(L, p, name, m, indices);
    } else {
      vertices = readAccessors(L, p, position->second, name, m, indices);
    }
    const std::size_t n = indices.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (n % 3 != 0) {
        L.fail(name + ": TRIANGLES primitive with " + std::to_string(n) + " indices (not a multiple of 3)");
      }
      for (std::size_t i = 0; i < n; i += 3) {
        m.triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
      }
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      // Every other triangle swaps its first two vertices to keep the strip's winding.
      for (std::size_t i = 0; i + 2 < n; ++i) {
        if (i % 2 == 0)
          m.triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
        else
          m.triangles.push_back({indices[i + 1], indices[i], indices[i + 2]});
      }
    } else {
      for (std::size_t i = 1; i + 1 < n; ++i) {
        m.triangles.push_back({indices[i], indices[i + 1], indices[0]});
      }
    }
    std::size_t outOfRange = 0;
    for (std::uint32_t i : indices) outOfRange += i >= vertices ? 1 : 0;
    if (outOfRange > 0) {
      L.warn(name + ": " + std::to_string(outOfRange) + " indices >= vertex count " + std::to_string(vertices) +
             "; their triangles are dropped");
    }
  } catch (const SkipPrimitive& skip) {
    L.warn(name + ": " + skip.why + "; primitive dropped");
    ++L.primitivesSkipped;
    out.skipped = true;
    return out;
  }
  out.report.inputVertices = out.mesh.positions.size();
  out.report.inputFaces = out.mesh.triangles.size();
  geo::cleanMesh(out.mesh, out.report);
  if (out.report.droppedTotal() > 0) {
    ++L.primitivesWithDrops;
    L.drops.droppedInvalidIndex += out.report.droppedInvalidIndex;
    L.drops.droppedNonFinite += out.report.droppedNonFinite;
    L.drops.droppedDegenerate += out.report.droppedDegenerate;
    L.drops.droppedDuplicate += out.report.droppedDuplicate;
  }
  if (out.report.hugeCoordinates > 0) {
    L.warn(name + ": " + std::to_string(out.report.hugeCoordinates) +
           " vertices with coordinates beyond 1e6 (kept; precision suffers)");
  }
  return out;
}

}  // namespace penumbra::detail
