// Headless GL 4.5 core contexts: EGL surfaceless (default; also NVIDIA's EGL) and OSMesa.
// Both backends are in one binary; the active one supplies every GL entry point.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "core/names.h"

namespace penumbra::gl {

enum class Backend { Egl, OSMesa };
inline constexpr Named<Backend> kBackendNames[] = {{Backend::Egl, "egl"}, {Backend::OSMesa, "osmesa"}};
inline const char* toString(Backend b) { return nameOf(kBackendNames, b); }

class Context {
 public:
  // Creates and makes current a GL 4.5 core context with KHR_debug output routed to the log.
  // Throws penumbra::Error(..., ExitCode::NoContext) when no context can be made.
  static std::unique_ptr<Context> create(Backend backend);
  virtual ~Context();

  // Makes this context current again (after another was made current) and reloads the entry
  // points from its backend.
  virtual void makeCurrent() = 0;

  Backend backend() const { return backend_; }
  const std::string& renderer() const { return renderer_; }  // GL_RENDERER
  const std::string& version() const { return version_; }    // GL_VERSION
  const std::string& vendor() const { return vendor_; }
  int maxTextureSize() const;  // GL_MAX_TEXTURE_SIZE: the largest image a Renderer makes

  // GL errors and high-severity debug messages seen since the last call (tests fail on any).
  static int takeErrorCount();
  // Drains glGetError; counts and logs each error with `where`.
  static void checkErrors(const char* where);
  // Runs `allocate` (one GL allocation: a texture or buffer store) and returns false when the GL
  // ran out of memory for it (GL_OUT_OF_MEMORY), which is then neither logged nor counted as a
  // GL error: the caller reports it as a penumbra::Error. Other GL errors count as usual.
  static bool tryAllocate(const std::function<void()>& allocate, const char* where);

 protected:
  explicit Context(Backend b) : backend_(b) {}
  void loadEntryPoints(void* (*getProc)(const char*));

 private:
  Backend backend_;
  std::string renderer_, version_, vendor_;
};

}  // namespace penumbra::gl
