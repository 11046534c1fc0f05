// The glTF loader's shared state and its primitive conversion (gltf_primitives.cpp: accessors
// checked against their bufferViews, compressed streams decoded, triangles assembled), used by
// gltf_loader.cpp. Internal to the scene library.
#pragma once

#include <tiny_gltf.h>

#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/loaders.h"

namespace penumbra::detail {

struct Loader {
  std::string path;
  std::string file;  // file name, for mesh names
  const tinygltf::Model& gltf;
  const Json& json;
  Model& out;
  LoadOptions options;
  // Drops summed over distinct primitives, reported once per file rather than per primitive
  // (CAD exports have hundreds); each SceneMesh keeps its own counts in its report.
  geo::MeshReport drops;
  std::size_t primitivesWithDrops = 0;
  std::size_t primitivesSkipped = 0;  // points, lines, no POSITION, sparse
  // KHR_mesh_quantization is used: attributes may be stored as (un)normalized integers.
  bool quantized = false;
  // The decoded bytes of the bufferViews compressed with EXT_meshopt_compression.
  std::map<int, std::vector<unsigned char>> decodedViews;

  std::string dropSummary() const {
    std::string s;
    auto add = [&](std::size_t n, const char* what) {
      if (n) s += (s.empty() ? "" : ", ") + std::to_string(n) + " " + what;
    };
    add(drops.droppedInvalidIndex, "with an index out of range");
    add(drops.droppedNonFinite, "with non-finite positions");
    add(drops.droppedDegenerate, "degenerate");
    add(drops.droppedDuplicate, "duplicate");
    return s;
  }

  [[noreturn]] void fail(const std::string& what) const { throw Error(path, what); }
  void warn(const std::string& what) { out.warnings.push_back(path + ": " + what); }
};

// A primitive converted to a cleaned triangle mesh (or skipped with a warning).
struct Primitive {
  geo::TriangleMesh mesh;
  geo::MeshReport report;
  int material = -1;
  bool skipped = false;
};

// Converts primitive `p` of the file (`name` names it in messages): its accessors, or its Draco
// stream, read and checked; strips and fans to triangles; the mesh cleaned and its drops counted.
Primitive convertPrimitive(Loader& L, const tinygltf::Primitive& p, const std::string& name);

}  // namespace penumbra::detail
