// EXT_meshopt_compression (https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Vendor/
// EXT_meshopt_compression) and KHR_draco_mesh_compression (.../Khronos/KHR_draco_mesh_compression)
// decoded with Debian's libmeshoptimizer and libdraco. The libraries assert their preconditions
// (strides, counts) only in debug builds, so every one of them is checked here first.
#include "scene/gltf_compression.h"

#include <tiny_gltf.h>

#include <draco/compression/decode.h>
#include <meshoptimizer.h>

#include <fmt/format.h>

#include "core/error.h"
#include "core/memory.h"

namespace penumbra::detail {

namespace {

// A non-negative integer property of a JSON object, or `fallback` when absent; a present value
// of another type is an error.
std::uint64_t unsignedOf(const Json& object, const char* key, const std::string& path, const std::string& what,
                         bool required) {
  const auto it = object.find(key);
  if (it == object.end()) {
    if (required) throw Error(path, what + ": '" + key + "' missing");
    return 0;
  }
  if (!it->is_number_unsigned() && !(it->is_number_integer() && it->get<long long>() >= 0))
    throw Error(path, what + ": '" + key + "' must be a non-negative integer, got " + shownJson(*it));
  return it->get<std::uint64_t>();
}

const Json* meshoptExtension(const Json& object) {
  const auto ext = object.find("extensions");
  if (ext == object.end() || !ext->is_object()) return nullptr;
  const auto it = ext->find("EXT_meshopt_compression");
  return it == ext->end() ? nullptr : &*it;
}

// One compressed bufferView into `out` (byteLength bytes, zero beyond count * byteStride).
void decodeMeshoptView(const std::string& path, const tinygltf::Model& gltf, const tinygltf::BufferView& view,
                       const Json& ext, const std::string& what, std::vector<unsigned char>& out) {
  auto fail = [&](const std::string& why) { throw Error(path, what + ": " + why); };
  if (!ext.is_object()) fail("the extension must be an object");
  const std::uint64_t buffer = unsignedOf(ext, "buffer", path, what, true);
  const std::uint64_t offset = unsignedOf(ext, "byteOffset", path, what, false);
  const std::uint64_t length = unsignedOf(ext, "byteLength", path, what, true);
  const std::uint64_t stride = unsignedOf(ext, "byteStride", path, what, true);
  const std::uint64_t count = unsignedOf(ext, "count", path, what, true);
  const auto modeIt = ext.find("mode");
  if (modeIt == ext.end() || !modeIt->is_string()) fail("'mode' missing or not a string");
  const std::string mode = modeIt->get<std::string>();
  std::string filter = "NONE";
  if (const auto f = ext.find("filter"); f != ext.end()) {
    if (!f->is_string()) fail("'filter' must be a string, got " + shownJson(*f));
    filter = f->get<std::string>();
  }
  if (buffer >= gltf.buffers.size()) fail("buffer " + std::to_string(buffer) + " does not exist");
  const std::vector<unsigned char>& source = gltf.buffers[buffer].data;
  if (offset > source.size() || length > source.size() - offset) {
    fail("the compressed stream (offset " + std::to_string(offset) + ", length " + std::to_string(length) +
         ") overruns buffer " + std::to_string(buffer) + " (" + std::to_string(source.size()) + " bytes)");
  }
  // The stream's strides and counts, as the extension's specification restricts them.
  if (mode == "ATTRIBUTES") {
    if (stride == 0 || stride > 256 || stride % 4 != 0)
      fail("ATTRIBUTES byteStride " + std::to_string(stride) + " is not a multiple of 4 in [4, 256]");
  } else if (mode == "TRIANGLES" || mode == "INDICES") {
    if (stride != 2 && stride != 4) fail(mode + " byteStride must be 2 or 4");
    if (mode == "TRIANGLES" && count % 3 != 0)
      fail("TRIANGLES count " + std::to_string(count) + " is not a multiple of 3");
  } else {
    fail("unknown mode '" + mode + "' (ATTRIBUTES, TRIANGLES or INDICES)");
  }
  const bool filtered = filter != "NONE";
  if (filtered && mode != "ATTRIBUTES") fail("filter " + filter + " on a " + mode + " stream");
  if (filter == "OCTAHEDRAL" && stride != 4 && stride != 8) fail("OCTAHEDRAL filter needs byteStride 4 or 8");
  if (filter == "QUATERNION" && stride != 8) fail("QUATERNION filter needs byteStride 8");
  if (filtered && filter != "OCTAHEDRAL" && filter != "QUATERNION" && filter != "EXPONENTIAL")
    fail("unknown filter '" + filter + "'");
  // The decoded size, declared before anything is allocated: count * byteStride must fit in the
  // bufferView (which the loader reads as usual) and in memory.
  if (count == 0) fail("count is 0");
  if (count > view.byteLength / stride) {
    fail(std::to_string(count) + " elements of " + std::to_string(stride) + " bytes do not fit in the bufferView's " +
         std::to_string(view.byteLength) + " bytes");
  }
  checkMemory(path, what + " decoding " + std::to_string(view.byteLength) + " bytes", double(view.byteLength));
  out.assign(view.byteLength, 0);
  const unsigned char* stream = source.data() + offset;
  int rc = 0;
  if (mode == "ATTRIBUTES")
    rc = meshopt_decodeVertexBuffer(out.data(), count, stride, stream, length);
  else if (mode == "TRIANGLES")
    rc = meshopt_decodeIndexBuffer(out.data(), count, stride, stream, length);
  else
    rc = meshopt_decodeIndexSequence(out.data(), count, stride, stream, length);
  if (rc != 0) {
    fail("the " + mode + " stream does not decode (meshoptimizer " +
         (rc == -1 ? std::string("does not know its version") : "error " + std::to_string(rc)) + ")");
  }
  if (filter == "OCTAHEDRAL")
    meshopt_decodeFilterOct(out.data(), count, stride);
  else if (filter == "QUATERNION")
    meshopt_decodeFilterQuat(out.data(), count, stride);
  else if (filter == "EXPONENTIAL")
    meshopt_decodeFilterExp(out.data(), count, stride);
}

}  // namespace

bool isMeshoptFallbackBuffer(const Json& buffer) {
  const Json* ext = meshoptExtension(buffer);
  if (!ext || !ext->is_object()) return false;
  const auto fallback = ext->find("fallback");
  return fallback != ext->end() && fallback->is_boolean() && fallback->get<bool>();
}

std::map<int, std::vector<unsigned char>> decodeMeshoptViews(const std::string& path, const tinygltf::Model& gltf,
                                                             const Json& json) {
  std::map<int, std::vector<unsigned char>> decoded;
  const auto views = json.find("bufferViews");
  if (views == json.end() || !views->is_array()) return decoded;
  for (std::size_t i = 0; i < views->size() && i < gltf.bufferViews.size(); ++i) {
    const Json* ext = meshoptExtension((*views)[i]);
    if (!ext) continue;
    const std::string what = "bufferView " + std::to_string(i) + " (EXT_meshopt_compression)";
    decodeMeshoptView(path, gltf, gltf.bufferViews[i], *ext, what, decoded[int(i)]);
  }
  return decoded;
}

bool hasDraco(const tinygltf::Primitive& p) { return p.extensions.count("KHR_draco_mesh_compression") > 0; }

DracoPrimitive decodeDraco(const std::string& path, const tinygltf::Model& gltf, const tinygltf::Primitive& p,
                           const std::string& name) {
  const std::string what = name + " (KHR_draco_mesh_compression)";
  auto fail = [&](const std::string& why) { throw Error(path, what + ": " + why); };
  const tinygltf::Value& ext = p.extensions.at("KHR_draco_mesh_compression");
  if (!ext.IsObject()) fail("the extension must be an object");
  const tinygltf::Value& viewValue = ext.Get("bufferView");
  if (!viewValue.IsInt() || viewValue.GetNumberAsInt() < 0 ||
      std::size_t(viewValue.GetNumberAsInt()) >= gltf.bufferViews.size())
    fail("'bufferView' missing or not a bufferView");
  const tinygltf::BufferView& view = gltf.bufferViews[std::size_t(viewValue.GetNumberAsInt())];
  if (view.buffer < 0 || std::size_t(view.buffer) >= gltf.buffers.size()) fail("its bufferView has no buffer");
  const std::vector<unsigned char>& data = gltf.buffers[std::size_t(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail("its bufferView overruns buffer " + std::to_string(view.buffer));
  const tinygltf::Value& attributes = ext.Get("attributes");
  if (!attributes.IsObject()) fail("'attributes' missing or not an object");

  // The counts the accessors declare: the stream must decode to exactly these (the extension's
  // specification), and they bound what is allocated for it.
  auto declared = [&](int accessor, const char* role) -> std::uint64_t {
    if (accessor < 0 || std::size_t(accessor) >= gltf.accessors.size())
      fail(std::string(role) + " accessor " + std::to_string(accessor) + " does not exist");
    return gltf.accessors[std::size_t(accessor)].count;
  };
  const auto position = p.attributes.find("POSITION");
  if (position == p.attributes.end()) fail("no POSITION attribute");
  const std::uint64_t vertices = declared(position->second, "POSITION");
  const std::uint64_t indices = p.indices >= 0 ? declared(p.indices, "indices") : 0;
  // Decoded attributes (32 bytes a vertex here, about as much inside Draco) and the corner table.
  checkMemory(path, what + " decoding " + std::to_string(vertices) + " vertices",
              double(vertices) * 64.0 + double(indices) * 16.0);

  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data.data() + view.byteOffset), view.byteLength);
  const auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) fail("not a Draco stream (" + type.status().error_msg_string() + ")");
  if (type.value() != draco::TRIANGULAR_MESH) fail("the Draco stream is a point cloud, not a triangle mesh");
  draco::Decoder decoder;
  auto decodedOr = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decodedOr.ok()) fail("the stream does not decode (" + decodedOr.status().error_msg_string() + ")");
  const std::unique_ptr<draco::Mesh> mesh = std::move(decodedOr).value();
  if (mesh->num_points() != vertices) {
    fail("decodes to " + std::to_string(mesh->num_points()) + " vertices but POSITION declares " +
         std::to_string(vertices));
  }
  if (p.indices >= 0 && std::uint64_t(mesh->num_faces()) * 3 != indices) {
    fail("decodes to " + std::to_string(mesh->num_faces()) + " triangles but the indices accessor declares " +
         std::to_string(indices) + " indices");
  }

  DracoPrimitive out;
  out.vertices = mesh->num_points();
  // Attribute `semantic` (components floats a vertex) into `into`, when the extension maps it.
  auto read = [&](const char* semantic, int components, std::vector<float>& into) {
    if (!attributes.Has(semantic)) return;
    const tinygltf::Value& id = attributes.Get(semantic);
    if (!id.IsInt() || id.GetNumberAsInt() < 0) fail(std::string("attribute id of ") + semantic + " is not an id");
    const draco::PointAttribute* att = mesh->GetAttributeByUniqueId(std::uint32_t(id.GetNumberAsInt()));
    if (!att)
      fail(std::string(semantic) + "'s attribute " + std::to_string(id.GetNumberAsInt()) + " is not in the stream");
    if (att->num_components() < components) {
      fail(std::string(semantic) + " has " + std::to_string(att->num_components()) + " components, not " +
           std::to_string(components));
    }
    into.resize(std::size_t(out.vertices) * std::size_t(components));
    for (std::uint32_t i = 0; i < out.vertices; ++i) {
      const draco::AttributeValueIndex value = att->mapped_index(draco::PointIndex(i));
      if (value.value() >= att->size() ||
          !att->ConvertValue<float>(value, std::int8_t(components), &into[std::size_t(i) * std::size_t(components)]))
        fail(std::string(semantic) + " value of vertex " + std::to_string(i) + " unreadable");
    }
  };
  read("POSITION", 3, out.positions);
  if (out.positions.empty()) fail("POSITION is not in the Draco stream");
  read("NORMAL", 3, out.normals);
  read("TEXCOORD_0", 2, out.uvs);
  out.indices.resize(std::size_t(mesh->num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh->face(f);
    for (int c = 0; c < 3; ++c) out.indices[std::size_t(f.value()) * 3 + std::size_t(c)] = face[c].value();
  }
  return out;
}

}  // namespace penumbra::detail
