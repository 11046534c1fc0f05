#include "gl/objects.h"
#include "gl/shader_source.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <regex>
#include <sstream>

#include <unistd.h>

#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "gl/context.h"

namespace penumbra::gl {

// ---- Live-object counts and limits ----------------------------------------------------------

namespace {
std::atomic<long> gLive[int(Kind::Count)];
std::atomic<unsigned> gLimitsGeneration{1};

double mib(double bytes) { return bytes / 1048576.0; }

// A GL allocation that may run out of memory: GL_OUT_OF_MEMORY becomes a one-line Error.
void allocateOrThrow(const std::string& what, double bytes, const std::function<void()>& allocate) {
  if (limits().maxAllocationBytes > 0 && bytes > limits().maxAllocationBytes)
    throw Error("GPU memory", fmt::format("out of memory allocating {} ({:.0f} MiB): more than this software "
                                          "renderer's {:.0f} MiB of system memory",
                                          what, mib(bytes), mib(limits().maxAllocationBytes)));
  if (!Context::tryAllocate(allocate, what.c_str()))
    throw Error("GPU memory", fmt::format("out of memory allocating {} ({:.0f} MiB)", what, mib(bytes)));
}
}  // namespace

const char* toString(Kind k) {
  static const char* const names[] = {"buffer",  "texture", "framebuffer", "vertex array",
                                      "program", "sampler", "shader",      "query"};
  return names[int(k)];
}

long liveObjectCount(Kind k) { return gLive[int(k)].load(); }
long liveObjectCount() {
  long n = 0;
  for (auto& c : gLive) n += c.load();
  return n;
}

namespace detail {
void objectCreated(Kind k) { ++gLive[int(k)]; }
void deleteObject(Kind k, GLuint id) {
  switch (k) {
    case Kind::Buffer:
      glDeleteBuffers(1, &id);
      break;
    case Kind::Texture:
      glDeleteTextures(1, &id);
      break;
    case Kind::Framebuffer:
      glDeleteFramebuffers(1, &id);
      break;
    case Kind::VertexArray:
      glDeleteVertexArrays(1, &id);
      break;
    case Kind::Program:
      glDeleteProgram(id);
      break;
    case Kind::Sampler:
      glDeleteSamplers(1, &id);
      break;
    case Kind::Shader:
      glDeleteShader(id);
      break;
    case Kind::Query:
      glDeleteQueries(1, &id);
      break;
    case Kind::Count:
      return;
  }
  --gLive[int(k)];
}
void invalidateLimits() { ++gLimitsGeneration; }
}  // namespace detail

const Limits& limits() {
  static thread_local Limits l;
  static thread_local unsigned generation = 0;
  if (generation != gLimitsGeneration.load()) {
    l = Limits{};
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &l.maxTextureSize);
    glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &l.maxCubeMapSize);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &l.maxArrayLayers);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &l.maxRenderbufferSize);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, l.maxViewport);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &l.maxFramebufferWidth);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &l.maxFramebufferHeight);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_LAYERS, &l.maxFramebufferLayers);
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &l.maxStorageBlockSize);
    glGetIntegerv(GL_SUBPIXEL_BITS, &l.subpixelBits);
    const GLubyte* r = glGetString(GL_RENDERER);
    const std::string renderer = r ? reinterpret_cast<const char*>(r) : "";
    if (renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos)
      l.maxAllocationBytes = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
    generation = gLimitsGeneration.load();
  }
  return l;
}

// ---- Query ----------------------------------------------------------------------------------

Query::Query(GLenum target) : target_(target) {
  GLuint id = 0;
  glCreateQueries(target, 1, &id);
  static_cast<Object&>(*this) = Object(id);
}
void Query::begin() const { glBeginQuery(target_, id()); }
void Query::end() const { glEndQuery(target_); }
std::uint64_t Query::result() const {
  GLuint64 v = 0;
  glGetQueryObjectui64v(id(), GL_QUERY_RESULT, &v);
  return std::uint64_t(v);
}

// ---- Buffer ----------------------------------------------------------------------------------

Buffer::Buffer(std::size_t bytes, const void* data) : size_(bytes) {
  if (bytes > std::size_t(std::numeric_limits<GLsizeiptr>::max()))
    throw Error("GPU memory", fmt::format("a buffer of {} bytes is too large", bytes));
  GLuint id = 0;
  glCreateBuffers(1, &id);
  static_cast<Object&>(*this) = Object(id);  // owned before anything can throw
  // GL rejects zero-size stores; keep a 16-byte buffer so binding an empty list is valid.
  allocateOrThrow("a buffer", double(bytes), [&] {
    glNamedBufferData(id, GLsizeiptr(bytes ? bytes : 16), bytes ? data : nullptr, GL_STATIC_DRAW);
  });
}

void Buffer::bindBase(GLenum target, GLuint index) const {
  if (target == GL_SHADER_STORAGE_BUFFER && limits().maxStorageBlockSize > 0 &&
      GLint64(size_) > limits().maxStorageBlockSize)
    throw Error("GPU memory", fmt::format("a storage buffer of {:.0f} MiB exceeds this GL's "
                                          "GL_MAX_SHADER_STORAGE_BLOCK_SIZE ({:.0f} MiB)",
                                          mib(double(size_)), mib(double(limits().maxStorageBlockSize))));
  glBindBufferBase(target, index, id());
}

void Buffer::bindRange(GLenum target, GLuint index, std::size_t offset, std::size_t bytes) const {
  PENUMBRA_CHECK(offset + bytes <= size_, "buffer range out of range");
  if (target == GL_SHADER_STORAGE_BUFFER && limits().maxStorageBlockSize > 0 &&
      GLint64(bytes) > limits().maxStorageBlockSize)
    throw Error("GPU memory", fmt::format("a storage block of {:.0f} MiB exceeds this GL's "
                                          "GL_MAX_SHADER_STORAGE_BLOCK_SIZE ({:.0f} MiB)",
                                          mib(double(bytes)), mib(double(limits().maxStorageBlockSize))));
  glBindBufferRange(target, index, id(), GLintptr(offset), GLsizeiptr(bytes));
}

void Buffer::write(const void* data, std::size_t bytes, std::size_t offset) const {
  PENUMBRA_CHECK(offset + bytes <= size_, "buffer write out of range");
  glNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data);
}

void Buffer::clear() const {
  PENUMBRA_CHECK(size_ % 4 == 0, "buffer clear of a size that is not a multiple of 4");
  glClearNamedBufferData(id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
}

void Buffer::read(void* data, std::size_t bytes, std::size_t offset) const {
  PENUMBRA_CHECK(offset + bytes <= size_, "buffer read out of range");
  glGetNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data);
}

// ---- Texture ---------------------------------------------------------------------------------

namespace {
struct FormatInfo {
  GLenum internal;
  int channels;
  int bytesPerTexel;
};
FormatInfo formatInfo(GLenum f) {
  switch (f) {
    case GL_R32F:
      return {f, 1, 4};
    case GL_R16F:
      return {f, 1, 2};
    case GL_RG32F:
      return {f, 2, 8};
    case GL_RGBA32F:
      return {f, 4, 16};
    case GL_RGBA16F:
      return {f, 4, 8};
    case GL_RGBA8:
      return {f, 4, 4};
    case GL_DEPTH_COMPONENT32F:
      return {f, 1, 4};
    case GL_R32UI:
      return {f, 1, 4};
    case GL_RGBA32UI:
      return {f, 4, 16};
    default:
      PENUMBRA_CHECK(false, "unknown texture format");
  }
}
GLenum pixelFormat(int channels) {
  static const GLenum fmts[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  PENUMBRA_CHECK(channels >= 1 && channels <= 4, "channels");
  return fmts[channels - 1];
}
void setSampling(GLuint id) {
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}
}  // namespace

namespace {
const char* formatName(GLenum f) {
  switch (f) {
    case GL_R32F:
      return "R32F";
    case GL_R16F:
      return "R16F";
    case GL_RG32F:
      return "RG32F";
    case GL_RGBA32F:
      return "RGBA32F";
    case GL_RGBA16F:
      return "RGBA16F";
    case GL_RGBA8:
      return "RGBA8";
    case GL_DEPTH_COMPONENT32F:
      return "DEPTH32F";
    case GL_R32UI:
      return "R32UI";
    case GL_RGBA32UI:
      return "RGBA32UI";
    default:
      return "?";
  }
}

// Checks a texture's size against the GL's limits (a one-line Error instead of a GL error),
// then creates it and allocates its storage (GL_OUT_OF_MEMORY: a one-line Error). layers 0: 2D.
GLuint createTexture(GLenum target, GLenum fmt, int w, int h, int layers, Texture& owner,
                     std::function<void(GLuint)> storage) {
  std::string what = layers > 0 ? fmt::format("a {} x {} x {} {} texture array", w, h, layers, formatName(fmt))
                                : fmt::format("a {} x {} {} texture", w, h, formatName(fmt));
  const Limits& l = limits();
  const int maxSize = target == GL_TEXTURE_CUBE_MAP_ARRAY ? l.maxCubeMapSize : l.maxTextureSize;
  if (w <= 0 || h <= 0 || (layers == 0 && target != GL_TEXTURE_2D) || layers < 0)
    throw Error("GPU memory", "cannot allocate " + what + " (empty)");
  if (w > maxSize || h > maxSize)
    throw Error("GPU memory", fmt::format("{} exceeds this GL's {} ({}); use a smaller image or map", what,
                                          target == GL_TEXTURE_CUBE_MAP_ARRAY ? "GL_MAX_CUBE_MAP_TEXTURE_SIZE"
                                                                              : "GL_MAX_TEXTURE_SIZE",
                                          maxSize));
  if (layers > l.maxArrayLayers)
    throw Error("GPU memory",
                fmt::format("{} exceeds this GL's GL_MAX_ARRAY_TEXTURE_LAYERS ({})", what, l.maxArrayLayers));
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  static_cast<Object<Kind::Texture>&>(owner) = Object<Kind::Texture>(id);  // deleted if storage fails
  const double bytes = double(w) * h * std::max(layers, 1) * formatInfo(fmt).bytesPerTexel;
  allocateOrThrow(what, bytes, [&] { storage(id); });
  setSampling(id);
  return id;
}
}  // namespace

Texture Texture::make2D(GLenum internalFormat, int width, int height) {
  Texture t;
  createTexture(GL_TEXTURE_2D, internalFormat, width, height, 0, t,
                [&](GLuint id) { glTextureStorage2D(id, 1, internalFormat, width, height); });
  t.w_ = width, t.h_ = height, t.layers_ = 0, t.fmt_ = internalFormat;
  return t;
}

Texture Texture::make2DArray(GLenum internalFormat, int width, int height, int layers) {
  Texture t;
  createTexture(GL_TEXTURE_2D_ARRAY, internalFormat, width, height, layers, t,
                [&](GLuint id) { glTextureStorage3D(id, 1, internalFormat, width, height, layers); });
  t.w_ = width, t.h_ = height, t.layers_ = layers, t.fmt_ = internalFormat;
  return t;
}

Texture Texture::makeCubeArray(GLenum internalFormat, int size, int cubes) {
  Texture t;
  createTexture(GL_TEXTURE_CUBE_MAP_ARRAY, internalFormat, size, size, 6 * cubes, t,
                [&](GLuint id) { glTextureStorage3D(id, 1, internalFormat, size, size, 6 * cubes); });
  t.w_ = t.h_ = size, t.layers_ = 6 * cubes, t.fmt_ = internalFormat;
  return t;
}

void Texture::uploadUint4(const std::uint32_t* texels) const {
  PENUMBRA_CHECK(fmt_ == GL_RGBA32UI, "uploadUint4 needs an RGBA32UI texture");
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (layers_ > 0)
    glTextureSubImage3D(id(), 0, 0, 0, 0, w_, h_, layers_, GL_RGBA_INTEGER, GL_UNSIGNED_INT, texels);
  else
    glTextureSubImage2D(id(), 0, 0, 0, w_, h_, GL_RGBA_INTEGER, GL_UNSIGNED_INT, texels);
}

void Texture::bind(GLuint unit) const { glBindTextureUnit(unit, id()); }

void Texture::bindImage(GLuint unit, GLenum access) const {
  glBindImageTexture(unit, id(), 0, layers_ > 0 ? GL_TRUE : GL_FALSE, 0, access, fmt_);
}

void Texture::clear(const glm::vec4& value) const {
  if (fmt_ == GL_R32UI || fmt_ == GL_RGBA32UI) {
    glm::uvec4 u(value);
    glClearTexImage(id(), 0, fmt_ == GL_R32UI ? GL_RED_INTEGER : GL_RGBA_INTEGER, GL_UNSIGNED_INT, &u);
  } else if (fmt_ == GL_DEPTH_COMPONENT32F) {
    glClearTexImage(id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &value.x);
  } else {
    glClearTexImage(id(), 0, GL_RGBA, GL_FLOAT, glm::value_ptr(value));
  }
}

Image Texture::read(int channels, int layer) const {
  PENUMBRA_CHECK(layer < 0 || layers_ > 0, "layer of a 2D texture");
  if (layers_ > 0 && layer < 0) {  // all layers, stacked vertically
    Image all(w_, h_ * layers_, channels);
    glGetTextureImage(id(), 0, pixelFormat(channels), GL_FLOAT, GLsizei(all.data.size() * sizeof(float)),
                      all.data.data());
    Context::checkErrors("Texture::read");
    return all;
  }
  Image img(w_, h_, channels);
  GLenum fmt = fmt_ == GL_DEPTH_COMPONENT32F ? GL_DEPTH_COMPONENT : pixelFormat(channels);
  if (layers_ == 0) {
    glGetTextureImage(id(), 0, fmt, GL_FLOAT, GLsizei(img.data.size() * sizeof(float)), img.data.data());
  } else {
    // One layer of an array: read all and copy out (arrays are small in the tests' sizes).
    std::vector<float> all(std::size_t(w_) * h_ * layers_ * channels);
    glGetTextureImage(id(), 0, fmt, GL_FLOAT, GLsizei(all.size() * sizeof(float)), all.data());
    std::copy_n(all.begin() + std::ptrdiff_t(img.data.size()) * layer, img.data.size(), img.data.begin());
  }
  Context::checkErrors("Texture::read");
  return img;
}

std::vector<std::uint32_t> Texture::readUint() const {
  PENUMBRA_CHECK(fmt_ == GL_R32UI, "readUint of a texture that is not R32UI");
  std::vector<std::uint32_t> out(std::size_t(w_) * h_ * std::max(layers_, 1));
  glGetTextureImage(id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(out.size() * sizeof(std::uint32_t)), out.data());
  Context::checkErrors("Texture::readUint");
  return out;
}

void Texture::upload(const float* data, int channels, int layer) const {
  if (layers_ == 0)
    glTextureSubImage2D(id(), 0, 0, 0, w_, h_, pixelFormat(channels), GL_FLOAT, data);
  else
    glTextureSubImage3D(id(), 0, 0, 0, layer, w_, h_, 1, pixelFormat(channels), GL_FLOAT, data);
}

std::size_t Texture::bytes() const {
  if (fmt_ == 0) return 0;  // no texture
  return std::size_t(w_) * h_ * std::max(1, layers_) * formatInfo(fmt_).bytesPerTexel;
}

// ---- Framebuffer -----------------------------------------------------------------------------

Framebuffer::Framebuffer(const std::vector<Attachment>& colors, const Texture* depth, int depthLayer) {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  static_cast<Object&>(*this) = Object(id);
  std::vector<GLenum> bufs;
  for (std::size_t i = 0; i < colors.size(); ++i) {
    const Texture& t = *colors[i].texture;
    GLenum at = GLenum(GL_COLOR_ATTACHMENT0 + i);
    if (colors[i].layer >= 0)
      glNamedFramebufferTextureLayer(id, at, t.id(), 0, colors[i].layer);
    else
      glNamedFramebufferTexture(id, at, t.id(), 0);
    bufs.push_back(at);
    w_ = t.width(), h_ = t.height();
  }
  glNamedFramebufferDrawBuffers(id, GLsizei(bufs.size()), bufs.data());
  if (depth) {
    if (depthLayer >= 0)
      glNamedFramebufferTextureLayer(id, GL_DEPTH_ATTACHMENT, depth->id(), 0, depthLayer);
    else
      glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth->id(), 0);
    w_ = depth->width(), h_ = depth->height();
  }
  const Limits& l = limits();
  if (w_ > l.maxViewport[0] || h_ > l.maxViewport[1])
    throw Error("GPU memory", fmt::format("a {} x {} render target exceeds this GL's GL_MAX_VIEWPORT_DIMS ({} x {})",
                                          w_, h_, l.maxViewport[0], l.maxViewport[1]));
  PENUMBRA_CHECK(glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
                 "framebuffer incomplete");
}

namespace {
std::vector<Framebuffer::Attachment> wholeTextures(const std::vector<const Texture*>& colors) {
  std::vector<Framebuffer::Attachment> a;
  for (auto* t : colors) a.push_back({t, -1});
  return a;
}
}  // namespace

Framebuffer::Framebuffer(const std::vector<const Texture*>& colors, const Texture* depth)
    : Framebuffer(wholeTextures(colors), depth) {}

Framebuffer Framebuffer::empty(int width, int height, int layers) {
  const Limits& l = limits();
  if (width <= 0 || height <= 0 || width > l.maxFramebufferWidth || height > l.maxFramebufferHeight ||
      width > l.maxViewport[0] || height > l.maxViewport[1] || layers > l.maxFramebufferLayers)
    throw Error(
        "GPU memory",
        fmt::format("a {} x {} x {} framebuffer without attachments exceeds this GL's "
                    "GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT/LAYERS ({} x {} x {}); use a smaller image or map",
                    width, height, layers, l.maxFramebufferWidth, l.maxFramebufferHeight, l.maxFramebufferLayers));
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  Framebuffer f;
  static_cast<Object&>(f) = Object(id);
  glNamedFramebufferParameteri(id, GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
  glNamedFramebufferParameteri(id, GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
  if (layers > 0) glNamedFramebufferParameteri(id, GL_FRAMEBUFFER_DEFAULT_LAYERS, layers);
  f.w_ = width, f.h_ = height;
  PENUMBRA_CHECK(glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
                 "framebuffer without attachments incomplete");
  return f;
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, id());
  glViewport(0, 0, w_, h_);
}

// ---- Sampler ---------------------------------------------------------------------------------

Sampler Sampler::make(bool linear, float border, GLenum compareFunc) {
  GLuint id = 0;
  glCreateSamplers(1, &id);
  Sampler s;
  static_cast<Object&>(s) = Object(id);
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, filter);
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, filter);
  glSamplerParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glSamplerParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float b[4] = {border, border, border, border};
  glSamplerParameterfv(id, GL_TEXTURE_BORDER_COLOR, b);
  if (compareFunc) {
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_FUNC, GLint(compareFunc));
  }
  return s;
}

void Sampler::bind(GLuint unit) const { glBindSampler(unit, id()); }
void Sampler::unbind(GLuint unit) { glBindSampler(unit, 0); }

// ---- VertexArray -----------------------------------------------------------------------------

VertexArray VertexArray::create() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  VertexArray v;
  static_cast<Object&>(v) = Object(id);
  return v;
}

VertexArray& VertexArray::attribute(GLuint index, int components, std::size_t offset, GLuint binding) {
  glEnableVertexArrayAttrib(id(), index);
  glVertexArrayAttribFormat(id(), index, components, GL_FLOAT, GL_FALSE, GLuint(offset));
  glVertexArrayAttribBinding(id(), index, binding);
  return *this;
}

VertexArray& VertexArray::attributeInt(GLuint index, int components, std::size_t offset, GLuint binding) {
  glEnableVertexArrayAttrib(id(), index);
  glVertexArrayAttribIFormat(id(), index, components, GL_INT, GLuint(offset));
  glVertexArrayAttribBinding(id(), index, binding);
  return *this;
}

VertexArray& VertexArray::vertexBuffer(const Buffer& b, std::size_t stride, GLuint binding) {
  glVertexArrayVertexBuffer(id(), binding, b.id(), 0, GLsizei(stride));
  return *this;
}

VertexArray& VertexArray::elementBuffer(const Buffer& b) {
  glVertexArrayElementBuffer(id(), b.id());
  return *this;
}

void VertexArray::bind() const { glBindVertexArray(id()); }

}  // namespace penumbra::gl
