// Private to src/scene/: the pieces loadScene() and defaultScene() are built from. The scene
// description is a JSON document (scene_json.cpp) that names geometry files (gltf_loader.cpp,
// geo::loadMeshFile) and procedural shapes (scene.cpp).
#pragma once

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace tinygltf {
class Model;
}

namespace penumbra::detail {

using Json = nlohmann::json;

// What one geometry file contributes, in the file's own space (glTF nodes already flattened).
// Material and texture indices are local to the model; materials may be empty (OBJ & co).
struct Model {
  std::vector<SceneMesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Light> lights;
  std::vector<std::string> warnings;
};

// glTF 2.0 (.gltf / .glb). Every URI must stay inside the file's folder. Throws
// penumbra::Error(path, ...) on anything malformed; recoverable problems become warnings.
Model loadGltf(const std::string& path, const LoadOptions& options = {});

// gltf_validate.cpp: reads a .gltf/.glb, checks everything tinygltf would trust (GLB container,
// URIs, buffer and bufferView bounds, data: URIs, required extensions) and parses it with
// tinygltf confined to the file's folder. Images are kept encoded (Image::as_is) for
// decodeGltfImage. `json` receives the document tinygltf parsed, for extensions it skips.
void parseGltfSandboxed(const std::string& path, tinygltf::Model& model, Json& json,
                        std::vector<std::string>& warnings);

// The sides an encoded glTF image (PNG/JPEG) declares in its header. Returns false with `why`
// set when the header is unreadable, the sides exceed 8192^2, or (PNG) the bytes cannot hold
// them (pngSizeProblem).
bool encodedImageSize(const std::vector<unsigned char>& encoded, int& width, int& height, std::string& why);

// Decodes an encoded glTF image (PNG/JPEG, at most 8192^2) to linear RGBA float, colour
// channels converted from sRGB when `srgb` (colour textures; data textures such as
// metallicRoughnessTexture are linear). Returns false with `why` set if it cannot.
bool decodeGltfImage(const std::vector<unsigned char>& encoded, Image& out, std::string& why, bool srgb = true);

// Bytes a decode of a `width` x `height` image takes at its peak (the decoder's 8- or 16-bit
// samples and the float RGBA texture), for checkMemory before decoding.
double decodeBytes(int width, int height);

// A texture file (.png sRGB-decoded, .exr linear) already resolved: what scene-file materials,
// lights and OBJ materials (map_Kd) load; its header only (sides, no pixels) without
// `options.decodeTextures`. EXR NaN/Inf texels are replaced by 0 and counted in `warnings`.
// Throws penumbra::Error naming the file (MemoryError when it does not fit).
Texture readTextureFile(const std::string& path, std::vector<std::string>& warnings, const LoadOptions& options);

// An OBJ file with its materials (obj_materials.cpp): the faces split by `usemtl` into one mesh
// per material, the `mtllib` files' Kd, map_Kd, d and Tr read into materials, everything else
// in them warned about.
Model loadObjModel(const std::string& path, const LoadOptions& options = {});

// Any supported geometry file by extension: glTF through loadGltf, OBJ/PLY/OFF/STL through
// geo::loadMeshFile.
Model loadGeometryFile(const std::string& path, const LoadOptions& options = {});

bool isGeometryExtension(const std::string& extension);  // lower-case, with the dot

// Procedural shapes, centred on the origin, +Y up, counter-clockwise seen from outside.
geo::TriangleMesh makeBox(glm::vec3 size);
geo::TriangleMesh makeSphere(float radius, int segments, int rings);
geo::TriangleMesh makeCylinder(float radius, float height, int segments, bool topCap, bool bottomCap);
// Open, single-sided, in the XZ plane facing +Y.
geo::TriangleMesh makeQuad(glm::vec2 size);
geo::TriangleMesh makeQuad(const glm::vec3 corners[4]);  // corners counter-clockwise from the front
geo::TriangleMesh makeDisk(float radius, int segments);

// Places geometry: positions by `m`, normals by its inverse transpose; a mirroring transform
// (negative determinant) reverses the triangle order so faces stay counter-clockwise outward.
void transformMesh(geo::TriangleMesh& mesh, const glm::mat4& m);

// transformMesh for a mesh that was cleaned in its own space: a finite matrix can still take a
// large coordinate beyond float range (a 1e30 node scale on a 1e10 coordinate, kept in
// tests/fuzz/regressions/), so triangles left with a non-finite vertex are dropped and counted
// in `report` like NaN input (hard-cases.md, bad inputs: "huge magnitudes", "never silently
// lost"). Returns how many triangles were dropped.
std::size_t placeMesh(geo::TriangleMesh& mesh, geo::MeshReport& report, const glm::mat4& m);

// Places a light: its frame follows `m` (the normal as a surface normal), its size scales with
// the lengths of the transformed tangent and bitangent.
Light transformLight(const Light& light, const glm::mat4& m);

// A camera document ({position, target, up, fov, near}) that frames the bounds from the front,
// slightly above.
Json framingCamera(glm::vec3 lo, glm::vec3 hi);

// "key=value" overrides (see scene.h) applied to the document in place. Throws
// penumbra::Error("override", ...) on a malformed pair or an array index out of range.
// Parses a scene file's or a glTF file's JSON (`root` "scene" or "glTF"; // and /* */ comments
// allowed in scene files only). JSON lets an object repeat a key and nlohmann (tinygltf too)
// keeps the last silently; a repeated key here throws penumbra::Error(path, "<item>: duplicate
// key '<key>'") naming where it is (`objects[1]`, `lights[0].spin`, `meshes[0]`). Invalid JSON
// throws Error(path, "invalid JSON: ...").
// The glTF extensions penumbra reads (a file may require these; others it uses are warned).
inline constexpr const char* kGltfExtensions[] = {"KHR_lights_punctual",
                                                  "EXT_lights_area",
                                                  "KHR_materials_emissive_strength",
                                                  "KHR_texture_transform",
                                                  "KHR_draco_mesh_compression",
                                                  "EXT_meshopt_compression",
                                                  "KHR_mesh_quantization"};

// Arrays and objects nested deeper than this are refused (Error(path, "<item>: nested deeper
// than 128 ...")) as the text is read: the conversions and messages after it recurse per level
// (a scene value or glTF `extras` 20,000 deep crashed them). Scene files need 4, glTF about 6.
inline constexpr std::size_t kMaxJsonDepth = 128;
Json parseJsonDocument(const std::string& text, const std::string& path, const std::string& root = "scene");
// The deepest nesting of arrays and objects in `text` (brackets outside strings; any text).
std::size_t jsonNestingDepth(const std::string& text);
// A JSON value as a message quotes it: compact, at most 80 characters (core/error.h abbreviate).
std::string shownJson(const Json& v);

void applyOverrides(Json& doc, const std::vector<std::string>& overrides);

// Interprets a scene document. `where` names it in messages (the file, or "<default scene>");
// relative paths resolve against `baseDir`. Empty `baseDir` forbids file references.
Scene interpretScene(const Json& doc, const std::string& where, const std::string& baseDir,
                     const LoadOptions& options = {});

// The document of the built-in scene.
Json defaultSceneDocument();

// The document for a bare geometry file: the file at the origin, a floor under its bounds, a
// camera framing it and a rect light above. `fileName` is relative to the file's folder.
Json bareGeometryDocument(const std::string& fileName, glm::vec3 lo, glm::vec3 hi);

// The procedural stained-glass emission texture ("procedural:stained-glass"): linear RGBA,
// saturated panes separated by dark leading.
Image stainedGlassImage(int size);

// Resolves a file reference from a scene document: a path relative to `baseDir` that stays
// inside it, or "assimp:<path>" under /usr/share/assimp/models. Throws Error(where, ...).
std::string resolveSceneReference(const std::string& reference, const std::string& baseDir, const std::string& where,
                                  const std::string& context);

// Why `path` (already percent-decoded) is not a plain relative path inside its folder, or ""
// if it is: no scheme, not absolute, no "..", no shell metacharacters.
std::string relativePathProblem(const std::string& path);

// True when `path` lies inside `folder` once both are made canonical (symlinks resolved).
bool isInsideFolder(const std::string& path, const std::string& folder);

std::string lowerExtension(const std::string& path);

}  // namespace penumbra::detail
