#include "render/context.h"

#include <GL/osmesa.h>
#include <dlfcn.h>

#include <mutex>
#include <stdexcept>
#include <string>

namespace render {

namespace {

// libOSMesa is opened when the first context is made, not linked: it brings Mesa and LLVM
// (52 MB mapped, 0.1 s to load and relocate), which every run of `ricochet` paid at start,
// `--version` and a replay without frames included. Never closed: its own exit-time state
// (and LeakSanitizer's suppression of its leaks, by library name) needs it mapped.
struct OsMesa {
  decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
  decltype(&OSMesaGetCurrentContext) getCurrentContext = nullptr;
  decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
};

template <class F>
void bind(void* library, const char* name, F& f) {
  void* symbol = dlsym(library, name);
  if (symbol == nullptr) {
    throw std::runtime_error(std::string("render: ") + RICOCHET_OSMESA_SONAME + " has no " + name +
                             " (Mesa's libOSMesa is needed, Debian package libosmesa6)");
  }
  f = reinterpret_cast<F>(symbol);
}

const OsMesa& osMesa() {
  static OsMesa api;
  static std::string error;
  static std::once_flag once;
  std::call_once(once, [] {
    void* library = dlopen(RICOCHET_OSMESA_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) {
      const char* why = dlerror();
      error = std::string("render: cannot load ") + RICOCHET_OSMESA_SONAME + ": " +
              (why != nullptr ? why : "unknown error") +
              " (install Debian's libosmesa6 to render frames)";
      return;
    }
    try {
      bind(library, "OSMesaCreateContextAttribs", api.createContextAttribs);
      bind(library, "OSMesaMakeCurrent", api.makeCurrent);
      bind(library, "OSMesaDestroyContext", api.destroyContext);
      bind(library, "OSMesaGetCurrentContext", api.getCurrentContext);
      bind(library, "OSMesaGetProcAddress", api.getProcAddress);
    } catch (const std::runtime_error& e) {
      error = e.what();
    }
  });
  if (!error.empty()) throw std::runtime_error(error);
  return api;
}

GlApi::Proc getProc(const char* name) {
  return osMesa().getProcAddress(name);
}

}  // namespace

bool osMesaLoaded() {
  void* library = dlopen(RICOCHET_OSMESA_SONAME, RTLD_NOW | RTLD_NOLOAD);
  if (library == nullptr) return false;
  dlclose(library);  // drops only the reference RTLD_NOLOAD took
  return true;
}

GlContext::GlContext() {
  const OsMesa& os = osMesa();
  // No depth, stencil or accumulation buffers: 2D shapes are drawn in order with blending.
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            0,
                            OSMESA_STENCIL_BITS,
                            0,
                            OSMESA_ACCUM_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            4,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            5,
                            0};
  OSMesaContext context = os.createContextAttribs(attributes, nullptr);
  if (context == nullptr) {
    throw std::runtime_error(
        "render: cannot create an OSMesa OpenGL 4.5 core context (needs Mesa's libOSMesa with "
        "llvmpipe, Debian package libosmesa6; check that GALLIUM_DRIVER is unset or llvmpipe)");
  }
  context_ = context;
  if (!os.makeCurrent(context, placeholder_, GL_UNSIGNED_BYTE, 1, 1)) {
    os.destroyContext(context);
    throw std::runtime_error("render: OSMesaMakeCurrent failed on a new context");
  }
  try {
    gl_.load(&getProc);
  } catch (...) {
    os.destroyContext(context);
    throw;
  }
  auto text = [this](GLenum name) {
    const GLubyte* s = gl_.GetString(name);
    return s == nullptr ? std::string("?") : std::string(reinterpret_cast<const char*>(s));
  };
  version_ = text(GL_VERSION);
  renderer_ = text(GL_RENDERER);
}

GlContext::~GlContext() {
  const OsMesa& os = osMesa();
  OSMesaContext context = static_cast<OSMesaContext>(context_);
  if (os.getCurrentContext() == context) os.makeCurrent(nullptr, nullptr, 0, 0, 0);
  os.destroyContext(context);
}

void GlContext::makeCurrent() {
  const OsMesa& os = osMesa();
  OSMesaContext context = static_cast<OSMesaContext>(context_);
  if (os.getCurrentContext() == context) return;
  if (!os.makeCurrent(context, placeholder_, GL_UNSIGNED_BYTE, 1, 1)) {
    throw std::runtime_error(
        "render: OSMesaMakeCurrent failed (is the context current on "
        "another thread?)");
  }
}

}  // namespace render
