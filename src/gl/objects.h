// RAII wrappers for GL objects (the shader-program builder is gl/program.h, included at the end
// for the code that uses both). Raw GL names stay inside these types; techniques hold wrappers
// and call GL (from gl/gl.h) only for draw state.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "gl/gl.h"

namespace penumbra::gl {

// Kinds of GL object the wrappers own; every one is counted while alive (liveObjectCount).
enum class Kind : int { Buffer, Texture, Framebuffer, VertexArray, Program, Sampler, Shader, Query, Count };
const char* toString(Kind k);

// GL objects created through these wrappers and not yet deleted, in this process (all
// contexts): of one kind, or of every kind. Resource tests check it returns to its baseline.
long liveObjectCount(Kind k);
long liveObjectCount();

namespace detail {
void objectCreated(Kind k);
void deleteObject(Kind k, GLuint id);  // deletes the GL name and uncounts it
void invalidateLimits();               // another context was made current
}  // namespace detail

// Move-only owner of one GL name of kind K.
template <Kind K>
class Object {
 public:
  Object() = default;
  explicit Object(GLuint id) : id_(id) {
    if (id_) detail::objectCreated(K);
  }
  ~Object() { reset(); }
  Object(Object&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Object& operator=(Object&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_) detail::deleteObject(K, id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

// The GL's limits, queried once per context (llvmpipe: 16384 px textures and viewports, 2048
// array layers, 128 MiB storage blocks). Allocations below check against them and throw a
// one-line penumbra::Error instead of raising a GL error.
struct Limits {
  GLint maxTextureSize = 0, maxCubeMapSize = 0, maxArrayLayers = 0, maxRenderbufferSize = 0;
  GLint maxViewport[2] = {0, 0};
  GLint maxFramebufferWidth = 0, maxFramebufferHeight = 0, maxFramebufferLayers = 0;
  GLint64 maxStorageBlockSize = 0;
  GLint subpixelBits = 0;  // GL_SUBPIXEL_BITS: window coordinates snap to 2^-bits pixel (llvmpipe 8)
  // Largest single allocation attempted: on a software renderer (llvmpipe) "GPU memory" is
  // system memory, which Linux overcommits, so an allocation beyond physical memory is refused
  // up front rather than risking the OOM killer when it is touched; 0: no bound (a GPU).
  double maxAllocationBytes = 0;
};
const Limits& limits();  // of the current context

class Buffer : public Object<Kind::Buffer> {
 public:
  Buffer() = default;
  // Immutable-size buffer with `bytes` of data (data may be null).
  Buffer(std::size_t bytes, const void* data);
  template <class T>
  explicit Buffer(const std::vector<T>& v) : Buffer(v.size() * sizeof(T), v.empty() ? nullptr : v.data()) {}
  std::size_t size() const { return size_; }
  void bindBase(GLenum target, GLuint index) const;
  // `bytes` from `offset` (a multiple of the target's offset alignment) to an indexed binding.
  void bindRange(GLenum target, GLuint index, std::size_t offset, std::size_t bytes) const;
  void write(const void* data, std::size_t bytes, std::size_t offset = 0) const;
  void read(void* data, std::size_t bytes, std::size_t offset = 0) const;
  void clear() const;  // every byte 0 (size a multiple of 4)

 private:
  std::size_t size_ = 0;
};

class Texture : public Object<Kind::Texture> {
 public:
  Texture() = default;
  // 2D texture with one level; nearest filtering, clamp to edge.
  static Texture make2D(GLenum internalFormat, int width, int height);
  // 2D array texture with `layers` layers.
  static Texture make2DArray(GLenum internalFormat, int width, int height, int layers);
  // Cube-map array of `cubes` cubes of size x size faces (layers() = 6 * cubes layer-faces).
  static Texture makeCubeArray(GLenum internalFormat, int size, int cubes);
  int width() const { return w_; }
  int height() const { return h_; }
  int layers() const { return layers_; }
  GLenum format() const { return fmt_; }
  void bind(GLuint unit) const;
  // Binds all layers as an image (load/store) of this texture's format.
  void bindImage(GLuint unit, GLenum access) const;
  void clear(const glm::vec4& value) const;  // all layers
  // Reads a float texture back as an Image with `channels` (1, 2, 3 or 4) channels. For an
  // array texture, layer -1 reads all layers stacked vertically (height * layers rows).
  Image read(int channels, int layer = -1) const;
  // Uploads float data (channels 1..4) to the whole texture (or one layer of an array).
  void upload(const float* data, int channels, int layer = -1) const;
  // Reads an R32UI texture (all layers) back: [layer][row][column].
  std::vector<std::uint32_t> readUint() const;
  // Uploads RGBA unsigned-integer texels to every layer (layer-face) of an RGBA32UI texture.
  void uploadUint4(const std::uint32_t* texels) const;
  std::size_t bytes() const;  // GPU memory estimate for reports

 private:
  int w_ = 0, h_ = 0, layers_ = 0;
  GLenum fmt_ = 0;
};

class Framebuffer : public Object<Kind::Framebuffer> {
 public:
  // A colour attachment: a texture, or one layer of an array texture.
  struct Attachment {
    const Texture* texture;
    int layer = -1;
  };
  Framebuffer() = default;
  // depthLayer >= 0: that layer of an array depth texture; -1: the whole texture (layered).
  Framebuffer(const std::vector<Attachment>& colors, const Texture* depth, int depthLayer = -1);
  // Colour attachments in order (draw buffers 0..n-1), optional depth texture.
  Framebuffer(const std::vector<const Texture*>& colors, const Texture* depth);
  // No attachments: rasterisation of a width x height viewport whose fragments only have side
  // effects (image and buffer stores); layers > 0: layered (geometry shaders set gl_Layer).
  static Framebuffer empty(int width, int height, int layers = 0);
  void bind() const;  // binds and sets the viewport to the attachment size
  int width() const { return w_; }
  int height() const { return h_; }

 private:
  int w_ = 0, h_ = 0;
};

// Sampling state bound to a texture unit in place of the texture's own (one depth texture read
// both raw and through a depth comparison).
class Sampler : public Object<Kind::Sampler> {
 public:
  Sampler() = default;
  // Clamp to a border of `border` (all channels); linear or nearest filtering; with
  // compareFunc != 0, depth comparison (GL_TEXTURE_COMPARE_MODE = COMPARE_REF_TO_TEXTURE).
  static Sampler make(bool linear, float border, GLenum compareFunc = 0);
  void bind(GLuint unit) const;
  static void unbind(GLuint unit);
};

class VertexArray : public Object<Kind::VertexArray> {
 public:
  VertexArray() = default;      // no GL object: members may be declared before a context exists
  static VertexArray create();  // needs the current context
  // Float attribute `index` of `components` floats at `offset` in vertex buffer binding `binding`.
  VertexArray& attribute(GLuint index, int components, std::size_t offset, GLuint binding = 0);
  VertexArray& attributeInt(GLuint index, int components, std::size_t offset, GLuint binding = 0);
  VertexArray& vertexBuffer(const Buffer& b, std::size_t stride, GLuint binding = 0);
  VertexArray& elementBuffer(const Buffer& b);
  void bind() const;
};

// A query object of one target (GL_ANY_SAMPLES_PASSED, GL_PRIMITIVES_GENERATED, ...): begin()
// and end() around draws; result() waits for the GL to finish them.
class Query : public Object<Kind::Query> {
 public:
  Query() = default;
  explicit Query(GLenum target);
  void begin() const;
  void end() const;
  std::uint64_t result() const;

 private:
  GLenum target_ = 0;
};

}  // namespace penumbra::gl

#include "gl/program.h"  // IWYU pragma: export
