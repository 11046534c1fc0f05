// The scene every technique renders: world-space triangle meshes with materials, a camera and
// lights. Loaders (scene JSON, glTF, OBJ/PLY/OFF/STL) all produce this; nothing here knows GL.
//
// Units: world units are whatever the scene uses; light intensity is emitted radiance for area
// lights (W sr^-1 m^-2 per unit of colour) and radiant intensity for point lights.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "shared/shared.h"  // NOLINT: shared with GLSL
#include "core/image.h"
#include "geometry/mesh.h"

namespace penumbra {

struct Texture {
  std::string source;         // file it came from, for messages
  Image image;                // linear RGBA float; empty when loaded without pixels (LoadOptions)
  int width = 0, height = 0;  // the sides the file declares, decoded or not
};

enum class AlphaMode { Opaque, Mask, Blend };

// Values match shared/shared/shared.h PENUMBRA_BRDF_* (checked below).
enum class BrdfModel { Lambert = 0, MetallicRoughness = 1 };
static_assert(int(BrdfModel::Lambert) == PENUMBRA_BRDF_LAMBERT &&
              int(BrdfModel::MetallicRoughness) == PENUMBRA_BRDF_METALLIC_ROUGHNESS);

struct Material {
  std::string name;
  glm::vec3 baseColor{0.8f};
  int baseColorTexture = -1;  // index into Scene::textures
  // Opacity of the surface as an occluder, in [0,1]. 1 = opaque. From glTF baseColorFactor.a
  // with alphaMode BLEND, or the scene file's "opacity" override. MASK: opacity is 0 or 1 by
  // alphaCutoff of the constant alpha; with a base colour texture whose alpha falls below the
  // cutoff the surface is alpha-tested (Scene::alphaTested): present where alphaFactor x the
  // texture's alpha >= alphaCutoff (shading/shaders/alpha_test.h). BLEND does not use the
  // texture's alpha for shadows (warned).
  float opacity = 1.0f;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  float alphaFactor = 1.0f;  // the constant alpha (glTF baseColorFactor.a) the texture's multiplies
  // The BRDF (shading/shaders/shading.h penumbraBrdf). Lambert: baseColor / pi (scene-file materials
  // without "metallic" or "roughness"). MetallicRoughness: the glTF 2.0 BRDF (Lambertian diffuse
  // + GGX with Smith masking, Schlick Fresnel) of glTF materials, OBJ materials with Ks and
  // scene-file materials that give "metallic" or "roughness".
  BrdfModel brdf = BrdfModel::Lambert;
  float metallic = 0.0f;   // [0, 1]
  float roughness = 1.0f;  // [0, 1], perceptual (alpha = roughness^2)
  // glTF metallicRoughnessTexture (linear; G scales roughness, B scales metallic), or -1.
  int metallicRoughnessTexture = -1;
};

// A rigid rotation at a constant rate (scene file "spin"), for `compare --frames`: the pose at
// time t is the rotation by degreesPerSecond * t about `axis` through `pivot`.
struct Spin {
  glm::vec3 axis{0.0f, 1.0f, 0.0f};  // unit
  glm::vec3 pivot{0.0f};
  float degreesPerSecond = 0.0f;
  bool active() const { return degreesPerSecond != 0.0f; }
  glm::mat4 at(float time) const;
};

// A mesh already transformed to world space (instances are flattened at load time).
struct SceneMesh {
  std::string name;  // "<file>#<mesh or node>" for messages
  geo::TriangleMesh mesh;
  geo::MeshReport report;
  int material = 0;  // index into Scene::materials
  Spin spin;         // the mesh as loaded is its pose at time 0
};

enum class LightShape { Point, Rect, Disk, Sphere };
static_assert(int(LightShape::Point) == PENUMBRA_LIGHT_POINT && int(LightShape::Rect) == PENUMBRA_LIGHT_RECT &&
              int(LightShape::Disk) == PENUMBRA_LIGHT_DISK && int(LightShape::Sphere) == PENUMBRA_LIGHT_SPHERE);

struct Light {
  std::string name;
  LightShape shape = LightShape::Rect;
  glm::vec3 position{0.0f, 4.0f, 0.0f};  // centre
  // Orthonormal frame. Rect and disk lights lie in the (tangent, bitangent) plane and emit
  // one-sided towards +normal (EXT_lights_area emits along local -Z: the loader converts).
  glm::vec3 normal{0.0f, -1.0f, 0.0f};
  glm::vec3 tangent{1.0f, 0.0f, 0.0f};
  glm::vec3 bitangent() const { return glm::cross(normal, tangent); }
  // Rect: full width (along tangent) and height (along bitangent). Disk and sphere: radius in
  // size.x. Point: unused.
  glm::vec2 size{1.0f, 1.0f};
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  // Emission texture (textured light): multiplies color * intensity, addressed by the light's
  // (u,v) in [0,1]^2 (u along tangent, v along bitangent; spheres: longitude/latitude).
  // Animated lights list frames; frame = floor(time * fps) mod frames.size().
  std::vector<int> emissionFrames;  // indices into Scene::textures; empty = untextured
  float fps = 0.0f;
  Spin spin;  // moves position, normal and tangent; the pose as loaded is time 0

  bool isArea() const { return shape != LightShape::Point; }
  float area() const;  // m^2 (rect w*h, disk pi r^2, sphere 4 pi r^2); 0 for points
  // The parallel-planes light size of PCSS-style penumbra estimates: half the side of the square
  // of the light's area (rect, disk) or of the disc a sphere shows; 0 for points.
  float penumbraHalfSize() const;
  int frameAt(float time) const;  // index into emissionFrames, or -1 if untextured
};

struct Camera {
  glm::vec3 position{0.0f, 3.0f, 8.0f};
  glm::vec3 target{0.0f, 0.0f, 0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovY = 45.0f;   // degrees, vertical
  float zNear = 0.05f;  // the far plane is at infinity
};

struct Scene {
  std::string name;        // file stem or "default"
  std::string sourcePath;  // empty for the built-in scene
  std::vector<SceneMesh> meshes;
  std::vector<Material> materials;  // never empty: [0] is the default material
  std::vector<Texture> textures;
  std::vector<Light> lights;
  Camera camera;
  int width = 256, height = 256;  // default output size
  glm::vec3 background{0.0f};
  std::vector<std::string> warnings;  // everything dropped or changed, one line each
  // World position of this scene's coordinate origin. Loaders read world coordinates and then
  // move the scene into the camera's frame (makeCameraRelative), so that floats keep their
  // detail around the camera whatever the world's offset (hard case 26); `origin` is the
  // camera's world position then, for anything that must report world coordinates.
  glm::dvec3 origin{0.0};

  std::size_t triangleCount() const;
  bool hasSemiOpaque() const;  // any mesh whose material opacity is in (0,1)
  // Whether material `index` is alpha-tested: alphaMode MASK, present (opacity 1), with a base
  // colour texture (loaded with its pixels) that has a texel whose alpha x alphaFactor is below
  // the cutoff. Such surfaces have holes; every occluder pass and the reference test them.
  bool alphaTested(int index) const;
  bool hasAlphaTested() const;  // any mesh with triangles whose material is alpha-tested
  // Axis-aligned bounds of all mesh vertices.
  void bounds(glm::vec3& lo, glm::vec3& hi) const;
  // The largest absolute value of each coordinate over all mesh vertices (0 without any): a
  // bound of the float magnitude of every surface point.
  glm::vec3 extent() const;
  // Translates every position (vertices, lights, camera, spin pivots) by -camera.position, in
  // place, and adds it to `origin`: the camera then sits at (0,0,0). Every technique and the
  // reference render in these coordinates (the Renderer makes a translated copy of a scene
  // whose camera is elsewhere), so a scene translated anywhere renders the same. Differences of
  // floats on one grid are exact, so a translation by a float already in the scene loses nothing.
  void makeCameraRelative();
  bool isCameraRelative() const { return camera.position == glm::vec3(0.0f); }
  // Any mesh or light with a spin.
  bool isAnimated() const;
  // A copy with every spinning mesh and light moved to its pose at `time` (seconds).
  Scene posedAt(float time) const;
};

// How much of a scene to read. `penumbra info` reads the textures' headers only (their sides),
// never their pixels: a 16384^2 texture costs it nothing.
struct LoadOptions {
  bool decodeTextures = true;
};

// Loads a scene file: .json (scene description) or a bare geometry file (.gltf, .glb, .obj,
// .ply, .off, .stl) which gets the default camera and light framing it. `overrides` are
// "key=value" pairs from --set, applied to the JSON before interpretation (dotted keys,
// array indices as numbers: "lights.0.size=[2,2]", "camera.fov=30"). Throws penumbra::Error
// naming the file and the problem.
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {},
                const LoadOptions& options = {});

// The built-in default scene: a textured rectangular area light (a procedural stained-glass
// texture) over a floor and occluders of different heights. Same overrides as loadScene.
Scene defaultScene(const std::vector<std::string>& overrides = {}, const LoadOptions& options = {});

}  // namespace penumbra
