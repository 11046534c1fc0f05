// Compressed glTF geometry, decoded with the real libraries before the loader reads it:
// EXT_meshopt_compression (meshoptimizer: a bufferView's bytes) and KHR_draco_mesh_compression
// (Draco: a primitive's attributes and indices). Every size a stream declares is checked against
// what holds it and against the memory budget before anything is allocated; a stream the
// decoder refuses is one Error naming the bufferView or the mesh. Internal to the scene library.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "scene/loaders.h"

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace penumbra::detail {

// EXT_meshopt_compression: the decoded bytes of every bufferView that carries the extension
// (by bufferView index; byteLength bytes each, as the bufferView declares), filters applied.
// `json` is the file's document. Throws Error(path, "bufferView N (EXT_meshopt_compression):
// ...") on a bad declaration or a stream the decoder refuses.
std::map<int, std::vector<unsigned char>> decodeMeshoptViews(const std::string& path, const tinygltf::Model& gltf,
                                                             const Json& json);

// A buffer of an EXT_meshopt_compression file that holds no data (`"fallback": true`, no uri):
// its bufferViews are all compressed ones.
bool isMeshoptFallbackBuffer(const Json& buffer);

// What a KHR_draco_mesh_compression stream of one primitive decodes to: per-vertex arrays of
// the attributes it holds (positions 3, normals 3, texture coordinates 2 floats a vertex) and
// the triangle list's indices.
struct DracoPrimitive {
  std::vector<float> positions, normals, uvs;
  std::uint32_t vertices = 0;
  std::vector<std::uint32_t> indices;
};

// Whether `p` carries KHR_draco_mesh_compression.
bool hasDraco(const tinygltf::Primitive& p);

// Decodes `p`'s Draco stream. `name` names the mesh in errors. The stream must decode to the
// counts `p`'s accessors declare (POSITION's vertex count, the indices' count) and hold the
// attributes the extension maps; throws Error(path, "<name> (KHR_draco_mesh_compression): ...")
// otherwise.
DracoPrimitive decodeDraco(const std::string& path, const tinygltf::Model& gltf, const tinygltf::Primitive& p,
                           const std::string& name);

}  // namespace penumbra::detail
