#include "pipeline/renderer.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/log.h"
#include "core/memory.h"
#include "pipeline/enclosure.h"
#include "shared/shared.h"  // NOLINT: shared with GLSL
#include "shading/light_integral.h"
#include "shading/ltc.h"
#include "shading/prefiltered_light.h"

namespace penumbra {

glm::mat4 viewFromWorld(const Camera& camera) { return glm::lookAt(camera.position, camera.target, camera.up); }

glm::mat4 clipFromViewReversedInfinite(const Camera& camera, float aspect) {
  // Reversed-Z infinite projection for glClipControl(..., GL_ZERO_TO_ONE): z_clip = near,
  // w_clip = -z_view, so depth = near / -z_view: 1 at the near plane, 0 at infinity. Points at
  // infinity (w = 0) land exactly on depth 0, which shadow-volume far caps rely on.
  float f = 1.0f / std::tan(glm::radians(camera.fovY) * 0.5f);
  glm::mat4 m(0.0f);
  m[0][0] = f / aspect;
  m[1][1] = f;
  m[2][3] = -1.0f;
  m[3][2] = camera.zNear;
  return m;
}

gl::Buffer lightSampleBuffer(const std::vector<glm::vec3>& positions, int samplesPerSet) {
  const glm::uvec4 header(std::uint32_t(samplesPerSet), 0u, 0u, 0u);
  std::vector<glm::vec4> pos(positions.size());
  for (std::size_t i = 0; i < pos.size(); ++i) pos[i] = glm::vec4(positions[i], 1.0f);
  gl::Buffer b(sizeof header + pos.size() * sizeof(glm::vec4), nullptr);
  b.write(&header, sizeof header);
  if (!pos.empty()) b.write(pos.data(), pos.size() * sizeof(glm::vec4), sizeof header);
  return b;
}

void setLightUniforms(const gl::Program& prog, const Light& light, const LightSampleSet& s) {
  prog.set("lightShape", int(light.shape));
  prog.set("lightPosition", light.position);
  prog.set("lightNormal", s.lightNormal);
  prog.set("lightTangent", light.tangent);
  prog.set("lightHalfExtent", 0.5f * light.size);
  prog.set("lightShapeRadius", light.size.x);
  prog.set("lightTextured", light.emissionFrames.empty() ? 0 : 1);
  prog.set("lightEmission", light.color * light.intensity);
  float scale = 1.0f;
  if (light.shape == LightShape::Rect || light.shape == LightShape::Disk) scale = light.area();
  if (light.shape == LightShape::Sphere) scale = float(M_PI) * light.size.x * light.size.x;
  prog.set("lightScale", scale);
  prog.set("sampleWeight", s.sampleWeight);
  prog.set("samplePattern", unsigned(s.pattern));
  prog.set("sampleSets", unsigned(s.setCount));
  prog.set("sampleK", unsigned(s.interleaveK));
  prog.set("sampleSeed", unsigned(s.seed));
}

void resolveVisibility(LightPass& pass, const gl::Program& program) {
  gl::Framebuffer fbo({&pass.visibility}, nullptr);
  fbo.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  pass.gpu.bindGBuffer();
  program.use();
  setLightUniforms(program, pass.light, pass.samples);
  gl::VertexArray vao = gl::VertexArray::create();
  vao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

// ---- GpuScene --------------------------------------------------------------------------------

namespace {
struct GVertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
  float plane;        // dot(normal, a vertex): the plane the G-buffer intersects with the pixel's ray
  glm::vec3 shading;  // the corner's shading normal (geo::ensureShadingNormals), or the face's
};
}  // namespace

GpuScene::GpuScene(const Scene& scene, int width, int height, std::size_t maxVertexBufferBytes)
    : scene_(scene), width_(width), height_(height) {
  float aspect = float(width) / float(height);
  clipFromWorld_ = clipFromViewReversedInfinite(scene.camera, aspect) * viewFromWorld(scene.camera);
  cameraPos_ = scene.camera.position;

  // Triangles are expanded (not indexed) so each vertex carries its face normal: the G-buffer
  // holds geometric normals, the ones the horizon rule and the reference's ray offset use.
  // They go into vertex buffers of at most maxVertexBufferBytes (whole triangles), each filled
  // from one staging array that is reused, so neither a GL size nor the staging memory grows
  // with the scene (one 2.1 GiB buffer crashed llvmpipe).
  const std::size_t triangles = scene.triangleCount();
  // On a software renderer the GL's buffers are this process's memory: check their total
  // before making them (each one alone is also checked by gl::Buffer).
  if (gl::limits().maxAllocationBytes > 0)
    checkMemory("GPU memory", fmt::format("the vertex buffers of {} triangles", triangles),
                double(triangles) * kGpuBytesPerTriangle);
  const std::size_t chunkVertices = 3 * std::max<std::size_t>(1, maxVertexBufferBytes / (3 * sizeof(GVertex)));
  std::vector<GVertex> verts;
  verts.reserve(std::min(chunkVertices, 3 * triangles));
  auto flush = [&] {
    if (verts.empty()) return;
    Chunk c;
    c.vertices = gl::Buffer(verts);
    c.vao = gl::VertexArray::create();
    c.vao.vertexBuffer(c.vertices, sizeof(GVertex))
        .attribute(0, 3, offsetof(GVertex, position))
        .attribute(1, 3, offsetof(GVertex, normal))
        .attribute(2, 2, offsetof(GVertex, uv))
        .attribute(3, 1, offsetof(GVertex, plane))
        .attribute(4, 3, offsetof(GVertex, shading));
    c.count = GLsizei(verts.size());
    chunks_.push_back(std::move(c));
    verts.clear();
  };
  for (auto& m : scene.meshes) {
    Draw d{int(chunks_.size()), GLint(verts.size()), 0, m.material};
    const auto& mesh = m.mesh;
    bool hasUv = mesh.uvs.size() == mesh.positions.size();
    bool hasNormals = mesh.normals.size() == mesh.positions.size();
    for (auto& t : mesh.triangles) {
      glm::vec3 p[3] = {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
      // In double: a float cross product of long edges loses the normal of a small triangle.
      glm::dvec3 nd = glm::cross(glm::dvec3(p[1]) - glm::dvec3(p[0]), glm::dvec3(p[2]) - glm::dvec3(p[0]));
      double len = glm::length(nd);
      glm::vec3 n = len > 0.0 ? glm::vec3(nd / len) : glm::vec3(0.0f, 1.0f, 0.0f);
      // The plane through the triangle's vertices with the float normal n: their mean offset.
      float plane = float((glm::dot(glm::dvec3(n), glm::dvec3(p[0])) + glm::dot(glm::dvec3(n), glm::dvec3(p[1])) +
                           glm::dot(glm::dvec3(n), glm::dvec3(p[2]))) /
                          3.0);
      for (int i = 0; i < 3; ++i) {
        // A missing, zero or non-finite vertex normal shades with the face's.
        glm::vec3 s = hasNormals ? mesh.normals[t[i]] : n;
        const float len = glm::length(s);
        s = len > 0.0f && std::isfinite(len) ? s / len : n;
        verts.push_back({p[i], n, hasUv ? mesh.uvs[t[i]] : glm::vec2(0.0f), plane, s});
      }
      if (verts.size() == chunkVertices) {  // the chunk is full: the mesh goes on in the next
        d.count = GLsizei(verts.size()) - d.first;
        if (d.count > 0) draws_.push_back(d);
        flush();
        d = Draw{int(chunks_.size()), 0, 0, m.material};
      }
    }
    d.count = GLsizei(verts.size()) - d.first;
    if (d.count > 0) draws_.push_back(d);
  }
  flush();
  for (std::size_t i = 0; i < scene.materials.size(); ++i) alphaTested_.push_back(scene.alphaTested(int(i)) ? 1 : 0);
  for (auto& d : draws_) {
    hasAlphaTested_ = hasAlphaTested_ || alphaTested_[std::size_t(d.material)];
    allOpaque_ = allOpaque_ && scene.materials[std::size_t(d.material)].opacity >= 1.0f;
  }
  allOpaque_ = allOpaque_ && !hasAlphaTested_;

  for (auto& t : scene.textures) {
    PENUMBRA_CHECK(!t.image.empty(), "texture " + t.source + " was loaded without its pixels");
    // A texture the GL cannot hold is the scene's problem, named by its file, not the
    // technique's or the reference's that happens to render first.
    gl::Texture tex;
    try {
      const int maxSize = gl::limits().maxTextureSize;
      if (maxSize > 0 && std::max(t.image.width, t.image.height) > maxSize)
        throw Error(
            "", fmt::format("{} x {} texels, more than this GL's {} a side", t.image.width, t.image.height, maxSize));
      tex = gl::Texture::make2D(GL_RGBA32F, t.image.width, t.image.height);
      if (t.image.channels == 4) {
        tex.upload(t.image.data.data(), 4);
      } else {  // loaders give RGBA; tolerate RGB
        Image rgba(t.image.width, t.image.height, 4, 1.0f);
        for (std::size_t i = 0; i < t.image.pixelCount(); ++i)
          for (int c = 0; c < std::min(3, t.image.channels); ++c)
            rgba.data[i * 4 + c] = t.image.data[i * t.image.channels + c];
        tex.upload(rgba.data.data(), 4);
      }
    } catch (const Error& e) {
      throw Error(t.source, std::string("texture cannot be uploaded: ") + e.what(), e.exitCode());
    }
    glTextureParameteri(tex.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(tex.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    materialTextures_.push_back(std::move(tex));
  }

  position_ = gl::Texture::make2D(GL_RGBA32F, width, height);
  normal_ = gl::Texture::make2D(GL_RGBA32F, width, height);
  albedo_ = gl::Texture::make2D(GL_RGBA16F, width, height);
  shading_ = gl::Texture::make2D(GL_RGBA32F, width, height);
  material_ = gl::Texture::make2D(GL_RGBA16F, width, height);
  depth_ = gl::Texture::make2D(GL_DEPTH_COMPONENT32F, width, height);
  fbo_ = gl::Framebuffer({&position_, &normal_, &albedo_, &shading_, &material_}, &depth_);
  program_ = gl::Program({"gbuffer.vert", "gbuffer.frag"});
  gl::Context::checkErrors("GpuScene upload");
}

void GpuScene::drawGBuffer(const gl::Program& program) const {
  int bound = -1;
  for (auto& d : draws_) {
    if (d.chunk != bound) chunks_[std::size_t(bound = d.chunk)].vao.bind();
    const Material& mat = scene_.materials[std::size_t(d.material)];
    program.set("baseColor", mat.baseColor);
    program.set("opacity", mat.opacity);
    program.set("materialId", d.material);
    program.set("brdfModel", int(mat.brdf));
    program.set("metallic", mat.metallic);
    program.set("roughness", mat.roughness);
    // Loaders only make indices into Scene::textures; one out of range binds nothing.
    auto bindTexture = [&](int index, int unit, const char* flag) {
      const bool tex = index >= 0 && std::size_t(index) < materialTextures_.size();
      program.set(flag, tex ? 1 : 0);
      if (tex) materialTextures_[std::size_t(index)].bind(unit);
    };
    bindTexture(mat.baseColorTexture, PENUMBRA_UNIT_MATERIAL_TEX, "hasTexture");
    setAlphaTest(program, d.material);
    bindTexture(mat.metallicRoughnessTexture, PENUMBRA_UNIT_MATERIAL_MR_TEX, "hasMetallicRoughnessTexture");
    glDrawArrays(GL_TRIANGLES, d.first, d.count);
  }
}

void GpuScene::setAlphaTest(const gl::Program& program, int material) const {
  const bool on = alphaTested_[std::size_t(material)] != 0;
  program.set("alphaTest", on ? 1 : 0);
  if (!on) return;
  const Material& mat = scene_.materials[std::size_t(material)];
  program.set("alphaFactor", mat.alphaFactor);
  program.set("alphaCutoff", mat.alphaCutoff);
  materialTextures_[std::size_t(mat.baseColorTexture)].bind(PENUMBRA_UNIT_MATERIAL_TEX);
}

void GpuScene::drawTriangles(GLsizei instances, Occluders which, const gl::Program& program) const {
  PENUMBRA_CHECK(!hasAlphaTested_ || which != Occluders::Opaque || program.location("alphaTest") >= 0,
                 "an occluder program without the alpha test (shading/shaders/alpha_test_depth.glsl) drawing a scene "
                 "with alpha-tested materials");
  if (which == Occluders::Opaque && allOpaque_) {  // one draw per chunk covers every occluder
    for (auto& c : chunks_) {
      c.vao.bind();
      glDrawArraysInstanced(GL_TRIANGLES, 0, c.count, instances);
    }
    return;
  }
  int bound = -1;
  for (auto& d : draws_) {
    float opacity = scene_.materials[std::size_t(d.material)].opacity;
    bool semi = opacity > 0.0f && opacity < 1.0f;
    if (opacity <= 0.0f || semi != (which == Occluders::SemiOpaque)) continue;
    if (d.chunk != bound) chunks_[std::size_t(bound = d.chunk)].vao.bind();
    if (semi) program.set("opacity", opacity);
    if (hasAlphaTested_ && !semi) setAlphaTest(program, d.material);
    glDrawArraysInstanced(GL_TRIANGLES, d.first, d.count, instances);
  }
}

void GpuScene::renderGBuffer() {
  fbo_.bind();
  const float zero[4] = {0, 0, 0, 0};
  for (int i = 0; i < 5; ++i) glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, i, zero);
  const float depthClear = 0.0f;  // reversed Z: 0 is infinitely far
  glClearNamedFramebufferfv(fbo_.id(), GL_DEPTH, 0, &depthClear);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  program_.use();
  program_.set("clipFromWorld", clipFromWorld_);
  program_.set("cameraPosition", cameraPos_);
  program_.set("worldFromClip", glm::mat4(glm::inverse(glm::dmat4(clipFromWorld_))));
  program_.set("viewportSize", glm::vec2(float(width_), float(height_)));
  drawGBuffer(program_);
  gl::Context::checkErrors("G-buffer");
}

void GpuScene::bindGBuffer() const {
  position_.bind(PENUMBRA_UNIT_GBUF_POSITION);
  normal_.bind(PENUMBRA_UNIT_GBUF_NORMAL);
  albedo_.bind(PENUMBRA_UNIT_GBUF_ALBEDO);
  shading_.bind(PENUMBRA_UNIT_GBUF_SHADING);
  material_.bind(PENUMBRA_UNIT_GBUF_MATERIAL);
}

CpuGBuffer GpuScene::readGBuffer() const {
  Image pos = position_.read(4), nrm = normal_.read(4), shading = shading_.read(4), albedo = albedo_.read(4),
        material = material_.read(4);
  CpuGBuffer g;
  g.width = width_, g.height = height_;
  g.camera = cameraPos_;
  g.origin = scene_.origin;
  std::size_t n = pos.pixelCount();
  g.position.resize(n), g.normal.resize(n), g.valid.resize(n);
  g.shadingNormal.resize(n), g.baseColor.resize(n), g.material.resize(n);
  auto vec3At = [](const Image& im, std::size_t i) {
    return glm::vec3(im.data[i * 4], im.data[i * 4 + 1], im.data[i * 4 + 2]);
  };
  for (std::size_t i = 0; i < n; ++i) {
    g.position[i] = vec3At(pos, i);
    g.normal[i] = vec3At(nrm, i);
    g.valid[i] = pos.data[i * 4 + 3] > 0.5f;
    g.shadingNormal[i] = vec3At(shading, i);
    g.baseColor[i] = vec3At(albedo, i);
    g.material[i] = vec3At(material, i);
  }
  return g;
}

std::size_t GpuScene::memoryBytes() const {
  std::size_t bytes =
      position_.bytes() + normal_.bytes() + albedo_.bytes() + shading_.bytes() + material_.bytes() + depth_.bytes();
  for (auto& c : chunks_) bytes += c.vertices.size();
  return bytes;
}

// ---- Renderer --------------------------------------------------------------------------------

namespace {
std::unique_ptr<Scene> cameraRelativeCopy(const Scene& scene) {
  if (scene.isCameraRelative()) return nullptr;
  auto local = std::make_unique<Scene>(scene);
  local->makeCameraRelative();
  return local;
}
}  // namespace

Renderer::Renderer(gl::Context& context, const Scene& given, const RenderSettings& settings)
    : local_(cameraRelativeCopy(given)), scene_(local_ ? *local_ : given), settings_(settings) {
  const Scene& scene = scene_;
  const int maxSize = context.maxTextureSize();
  if (settings.width <= 0 || settings.height <= 0 || settings.width > maxSize || settings.height > maxSize)
    throw Error("renderer",
                "image size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                    " outside 1.." + std::to_string(maxSize),
                ExitCode::Usage);
  if (scene.lights.empty()) throw Error(scene.sourcePath.empty() ? scene.name : scene.sourcePath, "scene has no light");
  gpu_ = std::make_unique<GpuScene>(scene, settings.width, settings.height, settings.maxVertexBufferBytes);
  color_ = gl::Texture::make2D(GL_RGBA32F, settings.width, settings.height);
  visibility_ = gl::Texture::make2D(GL_RGBA32F, settings.width, settings.height);

  colorFbo_ = gl::Framebuffer({&color_}, nullptr);
  emptyVao_ = gl::VertexArray::create();
  // The one shading program this renderer's mode needs (the mode is fixed per renderer).
  const bool ratio = settings.shading == ShadingMode::Ratio || settings.shading == ShadingMode::RatioExact;
  const char* mode = settings.shading == ShadingMode::PerSample ? "PER_SAMPLE" : ratio ? "RATIO" : "MODULATE";
  if (settings.shading == ShadingMode::RatioExact) {
    shade_ = gl::Program({"fullscreen.vert", "pipeline_shade.frag"}, {mode, "EXACT_UNSHADOWED"});
    exactUnshadowed_ = gl::Texture::make2D(GL_RGBA32F, settings.width, settings.height);
  } else {
    shade_ = gl::Program({"fullscreen.vert", "pipeline_shade.frag"}, {mode});
  }
  if (ratio) {
    const shading::LtcTable& table = shading::builtinLtcTable();
    ltc_ = gl::Texture::make2DArray(GL_RGBA32F, table.size(), table.size(), 2);
    ltc_.upload(&table.minv[0].x, 4, 0);
    ltc_.upload(&table.terms[0].x, 4, 1);
    glTextureParameteri(ltc_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(ltc_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  }
  filter_ = gl::Program({"fullscreen.vert", "pipeline_filter.frag"});
  if (settings.pipelineStatistics) statistics_ = gl::PipelineStatistics::create();
}

Renderer::~Renderer() = default;

const Renderer::Prefiltered* Renderer::prefilteredFor(const Light& light) {
  if (light.shape != LightShape::Rect && light.shape != LightShape::Disk) return nullptr;
  const Image* texture = lightEmissionTexture(scene_, light, settings_.time);
  if (!texture) return nullptr;
  const bool disk = light.shape == LightShape::Disk;
  auto [it, made] = prefiltered_.try_emplace({texture, disk});
  if (made) {
    const shading::PrefilteredLight chain = shading::prefilterLight(*texture, disk);
    Prefiltered& p = it->second;
    p.texture = gl::Texture::make2DArray(GL_RGBA32F, chain.size, chain.size, chain.levels);
    const std::size_t level = std::size_t(chain.size) * std::size_t(chain.size);
    for (int k = 0; k < chain.levels; ++k) p.texture.upload(&chain.texels[std::size_t(k) * level].x, 4, k);
    glTextureParameteri(p.texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(p.texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    p.sigma0 = chain.sigma0;
    p.levels = chain.levels;
  }
  return &it->second;
}

namespace {

// Values of `im` that are NaN or infinite, and the pixels holding them.
std::size_t nonFinitePixels(const Image& im) {
  std::size_t bad = 0;
  for (std::size_t i = 0; i < im.pixelCount(); ++i) {
    bool finite = true;
    for (int c = 0; c < im.channels; ++c)
      finite = finite && std::isfinite(im.data[i * std::size_t(im.channels) + std::size_t(c)]);
    bad += !finite;
  }
  return bad;
}

}  // namespace

FrameResult Renderer::render(Technique& technique, const std::string& name) {
  try {
    return renderFrame(technique, name);
  } catch (...) {
    // A technique that failed part-way may leave its fixed-function state: the next render
    // (compare goes on with the other techniques) starts from the state every pass expects.
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_CULL_FACE);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glUseProgram(0);
    gl::Context::checkErrors("failed frame");
    throw;
  }
}

// What the steps of one frame share.
struct Renderer::FrameState {
  FrameState(Technique& t, const std::string& n, GpuScene& g, ShadingMode shading)
      : technique(t),
        name(n),
        gpu(g),
        perSample(shading == ShadingMode::PerSample),
        exact(shading == ShadingMode::RatioExact),
        ratio(shading == ShadingMode::Ratio || exact),
        sumsSamples(perSample || ratio) {}
  Technique& technique;
  const std::string& name;
  GpuScene& gpu;
  bool perSample, exact, ratio;
  bool sumsSamples;  // shading reads every sample (eq. 6, the ratio), not V alone
  FrameResult result;
  bool haveCpuGBuffer = false;
  Image cpuRadiance;  // the lights a technique shaded itself (LightPass::cpuShading)
  std::size_t culledLights = 0;
  // The G-buffer read back to the CPU, once a frame on first use.
  const CpuGBuffer& cpuGBuffer() {
    if (!haveCpuGBuffer) {
      result.timer.harness("gbuffer readback", [&] { result.gbuffer = gpu.readGBuffer(); });
      haveCpuGBuffer = true;
    }
    return result.gbuffer;
  }
};

// What the steps of one light share.
struct Renderer::LightState {
  const Light& light;
  std::size_t index;
  LightSampleSet samples;
  gl::Buffer posBuf, lumBuf;         // PENUMBRA_SSBO_LIGHT_SAMPLES, PENUMBRA_SSBO_SAMPLE_RADIANCE
  bool wantSamples = false;          // the technique's per-sample results are kept or shaded from
  bool filter = false;               // interleaved sampling's gather filter runs
  const gl::Texture* vis = nullptr;  // the visibility shading reads (filtered or not)
  LightResult lr;
  CpuShading own;
};

FrameResult Renderer::renderFrame(Technique& technique, const std::string& name) {
  FrameState frame(technique, name, *gpu_, settings_.shading);
  frame.result.timer = StageTimer([] { glFinish(); });
  StageTimer& timer = frame.result.timer;
  timer.setCounter(statistics_.get());
  if (frame.perSample && !technique.providesPerSample() && !technique.shadesLights())
    throw Error(name.empty() ? "renderer" : name,
                "per-sample shading (eq. 6) needs a technique with per-sample visibility", ExitCode::Usage);

  if (prepared_ != technique.serial()) {
    timer.time("prepare", [&] { technique.prepare(scene_, *gpu_); });
    prepared_ = technique.serial();
  }
  timer.time("gbuffer", [&] { gpu_->renderGBuffer(); });
  const float background[4] = {scene_.background.r, scene_.background.g, scene_.background.b, 0};
  glClearNamedFramebufferfv(colorFbo_.id(), GL_COLOR, 0, background);
  for (std::size_t li = 0; li < scene_.lights.size(); ++li) renderLight(frame, li);
  return finishFrame(frame);
}

// One light: its samples uploaded, the technique's visibility (or the light culled), the
// interleaving filter, the light shaded into the image (or the technique's own shading added),
// the results read back and checked.
void Renderer::renderLight(FrameState& frame, std::size_t li) {
  const Light& light = scene_.lights[li];
  LightState l{light, li, makeLightSamples(scene_, light, settings_.sampling, settings_.time), {}, {}};
  const LightSampleSet& samples = l.samples;
  // A NaN pose (or light) would make every sample fail the horizon test: a finite, wrongly
  // dark image. Refused here, before any technique sees it.
  const auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite(light.position) || !std::all_of(samples.positions.begin(), samples.positions.end(), finite))
    throw Error(frame.name, fmt::format("light '{}': its position or light samples are NaN or infinite", light.name));
  std::vector<glm::vec4> lum(samples.luminance.size());
  for (std::size_t i = 0; i < lum.size(); ++i) lum[i] = glm::vec4(samples.luminance[i], 1.0f);
  l.posBuf = lightSampleBuffer(samples.positions, samples.count);
  l.lumBuf = gl::Buffer(lum);
  l.posBuf.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_LIGHT_SAMPLES);
  l.lumBuf.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_SAMPLE_RADIANCE);

  renderVisibility(frame, l);
  filterVisibility(frame, l);
  if (frame.technique.shadesLights())
    addOwnShading(frame, l);
  else
    shadeLight(frame, l);
  readBackLight(frame, l);
  frame.result.lights.push_back(std::move(l.lr));
}

// The technique's visibility for the light into visibility_ (and perSample_), or nothing where
// a closed mesh separates the light from the camera and the technique culls such lights.
void Renderer::renderVisibility(FrameState& frame, LightState& l) {
  Technique& technique = frame.technique;
  StageTimer& timer = frame.result.timer;
  const LightSampleSet& samples = l.samples;
  l.wantSamples = technique.providesPerSample() && (settings_.perSampleResults || frame.sumsSamples);
  if (l.wantSamples && (perSample_.width() != settings_.width || perSample_.layers() != samples.count))
    perSample_ = gl::Texture::make2DArray(GL_R32F, settings_.width, settings_.height, samples.count);
  visibility_.clear(glm::vec4(0.0f));
  // Pixels without a surface get no per-sample value from a technique: cleared like the
  // visibility, else they hold whatever the memory held (zink over lavapipe hands out freed
  // memory: an earlier texture's uint bits read as NaN, MultiView.SemiOpaque... flaked).
  if (l.wantSamples) perSample_.clear(glm::vec4(0.0f));
  l.lr.samples = samples.count;
  l.lr.sampleRadius.clear();
  if (l.light.shape == LightShape::Rect && samples.setCount == 1 && samples.uv.size() >= std::size_t(samples.count))
    for (int k = 0; k < samples.count; ++k)
      l.lr.sampleRadius.push_back(std::max(std::abs(2.0f * samples.uv[std::size_t(k)].x - 1.0f),
                                           std::abs(2.0f * samples.uv[std::size_t(k)].y - 1.0f)));
  LightPass pass{scene_,
                 l.light,
                 int(l.index),
                 samples,
                 *gpu_,
                 timer,
                 [&frame]() -> const CpuGBuffer& { return frame.cpuGBuffer(); },
                 visibility_,
                 l.wantSamples ? &perSample_ : nullptr,
                 &l.lr.perSample,
                 &l.lr.visibility,
                 &l.own};
  gpu_->bindGBuffer();
  const LightEnclosure* enclosure = nullptr;
  if (settings_.cullSeparatedLights && technique.cullsSeparatedLights()) {
    timer.time("light culling", [&] {
      if (!enclosures_)
        enclosures_ = std::make_unique<Enclosures>(
            scene_, nearPlaneReach(scene_.camera, double(settings_.width) / double(settings_.height)));
      enclosure = &enclosures_->classify(int(l.index), l.light, samples);
    });
    if (enclosure->separatedBy.empty() && !enclosure->straddled.empty() &&
        warned_.insert({technique.serial(), l.index}).second)
      PLOG_WARN(
          "{}: light '{}' has {} of {} samples on the other side of closed mesh '{}' from its centre: the "
          "technique sees the occluders from the centre, on one side of that surface only (light leaks "
          "through it; compare measures how much)",
          frame.name, l.light.name, enclosure->samplesInOtherCells, samples.positions.size(), enclosure->straddled);
  }
  if (enclosure && !enclosure->separatedBy.empty()) {
    ++frame.culledLights;  // visibility and per-sample results stay cleared: 0
  } else {
    technique.renderVisibility(pass);
    l.lr.unshadowed = timer.harness("unshadowed readback", [&] { return technique.unshadowedPixels(); });
  }
  gl::Context::checkErrors("visibility");
}

// Filters `source` into the bound framebuffer with interleaved sampling's gather over the
// K x K sets (blend state is the caller's).
void Renderer::drawInterleaveFilter(const gl::Texture& source, int interleaveK) {
  glDisable(GL_DEPTH_TEST);
  gpu_->bindGBuffer();
  source.bind(PENUMBRA_UNIT_FILTER_SOURCE);
  filter_.use();
  filter_.set("interleaveK", interleaveK);
  filter_.set("eyePosition", gpu_->cameraPosition());
  emptyVao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

// Interleaved sampling (DCS paper 5.2, Algorithm 2): the gather filter over the K x K sets,
// into filtered_; l.vis is what shading reads.
void Renderer::filterVisibility(FrameState& frame, LightState& l) {
  l.filter = settings_.interleaveFilter && l.samples.pattern == PixelPattern::Interleaved && l.samples.interleaveK > 1;
  if (l.filter && !filtered_) {  // only frames that interleave pay for these targets
    filtered_ = gl::Texture::make2D(GL_RGBA32F, settings_.width, settings_.height);
    filteredFbo_ = gl::Framebuffer({&filtered_}, nullptr);
  }
  if (l.filter && frame.sumsSamples && !lightColor_) {
    lightColor_ = gl::Texture::make2D(GL_RGBA32F, settings_.width, settings_.height);
    lightColorFbo_ = gl::Framebuffer({&lightColor_}, nullptr);
  }
  l.vis = &visibility_;
  if (l.filter) {
    frame.result.timer.time("interleave filter", [&] {
      filteredFbo_.bind();
      drawInterleaveFilter(visibility_, l.samples.interleaveK);
    });
    l.vis = &filtered_;
  }
}

// The technique shaded the light itself: its radiance is added to the image read back, its
// variances to the frame's (independent lights: variances add).
void Renderer::addOwnShading(FrameState& frame, LightState& l) {
  const auto rgbImage = [&](const Image& im) {
    return im.width == settings_.width && im.height == settings_.height && im.channels == 3;
  };
  if (l.own.radiance.pixelCount() == 0)
    throw Error(frame.name,
                fmt::format("light '{}': the technique shades its lights but gave no shaded image", l.light.name));
  if (!rgbImage(l.own.radiance) || (l.own.radianceVariance.pixelCount() && !rgbImage(l.own.radianceVariance)))
    throw Error(frame.name, fmt::format("light '{}': the technique's shaded image or its variance is not {}x{} RGB",
                                        l.light.name, settings_.width, settings_.height));
  const auto add = [&](Image& sum, const Image& term) {
    if (sum.pixelCount() == 0) sum = Image(settings_.width, settings_.height, 3, 0.0f);
    for (std::size_t i = 0; i < sum.data.size(); ++i) sum.data[i] += term.data[i];
  };
  add(frame.cpuRadiance, l.own.radiance);
  if (l.own.radianceVariance.pixelCount()) add(frame.result.colorVariance, l.own.radianceVariance);
}

// The light shaded into the image by the pipeline (shaders/pipeline_shade.frag), additively.
void Renderer::shadeLight(FrameState& frame, LightState& l) {
  StageTimer& timer = frame.result.timer;
  if (frame.exact) {
    const CpuGBuffer& g = frame.cpuGBuffer();
    const Image u = timer.time("exact unshadowed", [&] {
      return shading::unshadowedIntegral(g, scene_, l.light, settings_.time,
                                         shading::IntegratorOptions{.lightColour = false});
    });
    exactUnshadowed_.upload(u.data.data(), 3);
  }
  timer.time("shading", [&] {
    const gl::Program& prog = shade_;
    // Eq. 6 and the ratio estimator with interleaving: the light's term is shaded apart (from
    // the unfiltered per-sample results), then filtered into the image. Divergence from
    // Heitz et al. 2018, who filter the ratio: the unshadowed factor is smooth, so filtering
    // the product differs from it only where U varies within the K x K gather.
    const bool separate = frame.sumsSamples && l.filter;
    if (separate) {
      lightColorFbo_.bind();
      const float zero[4] = {0, 0, 0, 0};
      glClearNamedFramebufferfv(lightColorFbo_.id(), GL_COLOR, 0, zero);
    } else {
      colorFbo_.bind();
    }
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    gpu_->bindGBuffer();
    l.posBuf.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_LIGHT_SAMPLES);
    l.lumBuf.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_SAMPLE_RADIANCE);
    if (l.wantSamples) perSample_.bind(PENUMBRA_UNIT_SAMPLE_VIS);
    (frame.ratio ? visibility_ : *l.vis).bind(PENUMBRA_UNIT_VISIBILITY);
    prog.use();
    setLightUniforms(prog, l.light, l.samples);
    prog.set("eyePosition", gpu_->cameraPosition());
    if (frame.exact) exactUnshadowed_.bind(PENUMBRA_UNIT_UNSHADOWED);
    if (frame.ratio) {
      prog.set("ratioFromSamples", l.wantSamples ? 1 : 0);
      prog.set("ltcSize", float(ltc_.width()));
      ltc_.bind(PENUMBRA_UNIT_LTC);
      const Prefiltered* chain = prefilteredFor(l.light);
      prog.set("lightPrefiltered", chain ? 1 : 0);
      if (chain) {
        chain->texture.bind(PENUMBRA_UNIT_LIGHT_PREFILTERED);
        prog.set("prefilterSigma0", chain->sigma0);
        prog.set("prefilterLevels", chain->levels);
      }
    }
    emptyVao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    if (separate) {
      colorFbo_.bind();
      drawInterleaveFilter(lightColor_, l.samples.interleaveK);
    }
    glDisable(GL_BLEND);
  });
}

// The light's visibility and per-sample results read back, and checked: never a NaN, never a
// visibility outside [0, 1].
void Renderer::readBackLight(FrameState& frame, LightState& l) {
  LightResult& lr = l.lr;
  const int count = l.samples.count;
  frame.result.timer.harness("readback", [&] {
    // A CPU technique's own visibility is the buffer unless the filter changed it.
    if (l.filter || lr.visibility.pixelCount() == 0) {
      lr.visibility = l.vis->read(3);
    }
    if (l.wantSamples && settings_.perSampleResults && lr.perSample.empty()) {
      // GPU per-sample results: gather the layers into [pixel * N + k].
      std::size_t n = lr.visibility.pixelCount();
      lr.perSample.resize(n * std::size_t(count));
      Image layers = perSample_.read(1);
      for (std::size_t k = 0; k < std::size_t(count); ++k)
        for (std::size_t i = 0; i < n; ++i) lr.perSample[i * std::size_t(count) + k] = layers.data[k * n + i];
    }
  });
  if (std::size_t bad = nonFinitePixels(lr.visibility))
    throw Error(frame.name, fmt::format("light '{}': {} of {} visibility pixels are NaN or infinite", l.light.name, bad,
                                        lr.visibility.pixelCount()));
  // Eq. 2 is a weighted mean of transmittances: outside [0, 1] (beyond float rounding) is a
  // fault, never an image (a negative emission texel once gave -5).
  const auto [lo, hi] = std::minmax_element(lr.visibility.data.begin(), lr.visibility.data.end());
  if (lo != lr.visibility.data.end() && (*lo < -1e-4f || *hi > 1.0f + 1e-4f))
    throw Error(frame.name,
                fmt::format("light '{}': visibility outside [0, 1] (from {} to {})", l.light.name, *lo, *hi));
  lr.visibilityVariance = std::move(l.own.visibilityVariance);
  if (std::any_of(lr.perSample.begin(), lr.perSample.end(), [](float v) { return !std::isfinite(v); }))
    throw Error(frame.name,
                fmt::format("light '{}': per-sample visibility holds NaN or infinite values", l.light.name));
}

// The image read back (with the lights techniques shaded themselves added) and checked, the
// statistics and the memory the frame held.
FrameResult Renderer::finishFrame(FrameState& frame) {
  FrameResult& result = frame.result;
  Technique& technique = frame.technique;
  StageTimer& timer = result.timer;
  result.color = timer.harness("readback", [&] { return color_.read(3); });
  for (std::size_t i = 0; i < frame.cpuRadiance.data.size(); ++i) result.color.data[i] += frame.cpuRadiance.data[i];
  if (std::size_t bad = nonFinitePixels(result.color))
    throw Error(frame.name,
                fmt::format("{} of {} pixels of the shaded image are NaN or infinite", bad, result.color.pixelCount()));
  // Comparisons mask background pixels with it (RenderSettings::gbufferResults).
  if (settings_.gbufferResults) frame.cpuGBuffer();
  result.statistics = technique.statistics();
  if (gpu_->hasAlphaTested() && !technique.seesAlphaTest())
    result.notes.push_back(
        "alpha-tested occluders cast their whole triangles: its shadow volumes come from the meshes' edges and do not "
        "see the textures' holes");
  if (settings_.cullSeparatedLights && technique.cullsSeparatedLights())
    result.statistics.emplace_back("lights culled (a closed mesh between them and the camera)",
                                   double(frame.culledLights));
  result.memoryBytes = gpu_->memoryBytes() + color_.bytes() + visibility_.bytes() +
                       (filtered_ ? filtered_.bytes() : 0) + (lightColor_ ? lightColor_.bytes() : 0) +
                       (perSample_ ? perSample_.bytes() : 0) + (ltc_ ? ltc_.bytes() : 0) + technique.memoryBytes();
  for (const auto& [key, chain] : prefiltered_) result.memoryBytes += chain.texture.bytes();
  timer.setCounter(nullptr);
  gl::Context::checkErrors("frame");
  return std::move(result);
}

}  // namespace penumbra
