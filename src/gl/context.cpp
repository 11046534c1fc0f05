#include "gl/context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <atomic>
#include <cctype>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/log.h"
#include "gl/gl.h"
#include "gl/objects.h"

namespace penumbra {
#define X(type, name) type name = nullptr;
#include "gl/functions.inl"
#undef X
}  // namespace penumbra

namespace penumbra::gl {
namespace {

std::atomic<int> gErrorCount{0};
// Inside Context::tryAllocate: out-of-memory debug messages are the caller's to report.
thread_local bool gTrapOutOfMemory = false;
thread_local bool gSawOutOfMemory = false;

bool isOutOfMemoryMessage(const GLchar* message) {
  std::string m(message ? message : "");
  for (auto& c : m) c = char(std::tolower(static_cast<unsigned char>(c)));
  return m.find("out_of_memory") != std::string::npos || m.find("out of memory") != std::string::npos;
}

void GLAPIENTRY debugCallback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei, const GLchar* message,
                              const void*) {
  if (gTrapOutOfMemory && type == GL_DEBUG_TYPE_ERROR && isOutOfMemoryMessage(message)) {
    gSawOutOfMemory = true;
    PLOG_DEBUG("GL: {}", message);
    return;
  }
  if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH) {
    ++gErrorCount;
    PLOG_ERROR("GL: {}", message);
  } else if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) {
    PLOG_TRACE("GL: {}", message);
  } else {
    PLOG_DEBUG("GL: {}", message);
  }
}

[[noreturn]] void noContext(const std::string& what) { throw Error("GL context", what, ExitCode::NoContext); }

class EglContext final : public Context {
 public:
  EglContext() : Context(Backend::Egl) {
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    // Mesa: surfaceless platform. NVIDIA: the device platform (first device).
    if (getPlatformDisplay) display_ = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, nullptr, nullptr)) {
      display_ = EGL_NO_DISPLAY;
      auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
      EGLDeviceEXT devices[8];
      EGLint n = 0;
      if (queryDevices && getPlatformDisplay && queryDevices(8, devices, &n) && n > 0) {
        display_ = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
        if (display_ != EGL_NO_DISPLAY && !eglInitialize(display_, nullptr, nullptr)) display_ = EGL_NO_DISPLAY;
      }
    }
    if (display_ == EGL_NO_DISPLAY) noContext("EGL: no surfaceless or device display could be initialised");
    if (!eglBindAPI(EGL_OPENGL_API)) noContext("EGL: OpenGL API not available");
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              4,
                              EGL_CONTEXT_MINOR_VERSION,
                              5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_CONTEXT_OPENGL_DEBUG,
                              EGL_TRUE,
                              EGL_NONE};
    // EGL_KHR_no_config_context: no surface, so no config needed.
    context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (context_ == EGL_NO_CONTEXT) {
      EGLint cfgAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
      EGLConfig cfg;
      EGLint count = 0;
      if (eglChooseConfig(display_, cfgAttribs, &cfg, 1, &count) && count > 0)
        context_ = eglCreateContext(display_, cfg, EGL_NO_CONTEXT, attribs);
    }
    if (context_ == EGL_NO_CONTEXT) noContext("EGL: cannot create a GL 4.5 core context");
    makeCurrent();
  }
  void makeCurrent() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      noContext("EGL: cannot make the context current without a surface");
    loadEntryPoints([](const char* n) { return reinterpret_cast<void*>(eglGetProcAddress(n)); });
  }
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
  }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

// libOSMesa, loaded when an OSMesa context is asked for rather than linked: the EGL backend
// (NVIDIA's EGL through glvnd, bench/gpu.sh) then needs neither it nor the LLVM it pulls in.
struct OSMesaLibrary {
  decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
};

const OSMesaLibrary& osmesa() {
  static const OSMesaLibrary lib = [] {
    OSMesaLibrary l;
    void* h = nullptr;
    for (const char* name : {"libOSMesa.so.8", "libOSMesa.so"})
      if ((h = dlopen(name, RTLD_NOW | RTLD_LOCAL))) break;
    if (!h) return l;
    l.createContextAttribs = reinterpret_cast<decltype(l.createContextAttribs)>(dlsym(h, "OSMesaCreateContextAttribs"));
    l.makeCurrent = reinterpret_cast<decltype(l.makeCurrent)>(dlsym(h, "OSMesaMakeCurrent"));
    l.getProcAddress = reinterpret_cast<decltype(l.getProcAddress)>(dlsym(h, "OSMesaGetProcAddress"));
    l.destroyContext = reinterpret_cast<decltype(l.destroyContext)>(dlsym(h, "OSMesaDestroyContext"));
    return l;
  }();
  return lib;
}

class OSMesaBackend final : public Context {
 public:
  OSMesaBackend() : Context(Backend::OSMesa) {
    if (!osmesa().createContextAttribs || !osmesa().makeCurrent || !osmesa().getProcAddress || !osmesa().destroyContext)
      noContext("OSMesa: cannot load libOSMesa.so.8 (Debian libosmesa6) or one of its entry points");
    // OSMesa renders with Mesa's software rasterisers only (llvmpipe, softpipe): Mesa 22.3's
    // OSMesaCreateContextAttribs dereferences a null screen (SIGSEGV) when GALLIUM_DRIVER names
    // another driver (zink, or a typo), so say so instead of calling it.
    if (const char* d = std::getenv("GALLIUM_DRIVER")) {
      const std::string driver(d);
      if (!driver.empty() && driver != "llvmpipe" && driver != "softpipe")
        noContext("OSMesa: GALLIUM_DRIVER=" + driver + " is not one of OSMesa's drivers (llvmpipe, softpipe)");
    }
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    context_ = osmesa().createContextAttribs(attribs, nullptr);
    if (!context_) noContext("OSMesa: cannot create a GL 4.5 core context");
    makeCurrent();
  }
  void makeCurrent() override {
    // OSMesa needs a colour buffer to make a context current; all rendering goes to FBOs.
    if (!osmesa().makeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1))
      noContext("OSMesa: cannot make the context current");
    loadEntryPoints([](const char* n) { return reinterpret_cast<void*>(osmesa().getProcAddress(n)); });
  }
  ~OSMesaBackend() override { osmesa().destroyContext(context_); }

 private:
  OSMesaContext context_ = nullptr;
  std::vector<unsigned char> buffer_ = std::vector<unsigned char>(4, 0);
};

}  // namespace

std::unique_ptr<Context> Context::create(Backend backend) {
  std::unique_ptr<Context> c;
  if (backend == Backend::Egl)
    c = std::make_unique<EglContext>();
  else
    c = std::make_unique<OSMesaBackend>();
  return c;
}

Context::~Context() = default;

int Context::maxTextureSize() const {
  GLint size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &size);
  return int(size);
}

void Context::loadEntryPoints(void* (*getProc)(const char*)) {
  std::vector<std::string> missing;
#define X(type, name)                                      \
  penumbra::name = reinterpret_cast<type>(getProc(#name)); \
  if (!penumbra::name) missing.push_back(#name);
#include "gl/functions.inl"
#undef X
  if (!missing.empty()) noContext("missing GL entry point " + missing.front());
  detail::invalidateLimits();
  auto str = [](GLenum e) {
    const GLubyte* s = glGetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  renderer_ = str(GL_RENDERER);
  version_ = str(GL_VERSION);
  vendor_ = str(GL_VENDOR);
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 45) noContext("GL 4.5 required, got " + version_);
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(debugCallback, nullptr);
  // Conventions used everywhere (see docs/architecture.md "Conventions"): window row 0 is the top image row,
  // so readbacks need no flip and gl_FragCoord.xy is the image pixel; depth in [0,1] with
  // reversed Z (near = 1, infinity = 0) for precision.
  glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  checkErrors("context setup");
}

int Context::takeErrorCount() { return gErrorCount.exchange(0); }

void Context::checkErrors(const char* where) {
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
    ++gErrorCount;
    PLOG_ERROR("GL error 0x{:x} at {}", e, where);
  }
}

bool Context::tryAllocate(const std::function<void()>& allocate, const char* where) {
  checkErrors(where);  // earlier errors are not this allocation's
  gTrapOutOfMemory = true;
  gSawOutOfMemory = false;
  try {
    allocate();
  } catch (...) {
    gTrapOutOfMemory = false;
    throw;
  }
  gTrapOutOfMemory = false;
  bool ok = !gSawOutOfMemory;
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
    if (e == GL_OUT_OF_MEMORY) {
      ok = false;
      continue;
    }
    ++gErrorCount;
    PLOG_ERROR("GL error 0x{:x} at {}", e, where);
  }
  return ok;
}

}  // namespace penumbra::gl
