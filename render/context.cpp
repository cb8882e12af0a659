#include "render/context.h"

#include <GL/osmesa.h>

#include <stdexcept>

namespace render {

namespace {

GlApi::Proc getProc(const char* name) {
  return OSMesaGetProcAddress(name);
}

}  // namespace

GlContext::GlContext() {
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
  OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (context == nullptr) {
    throw std::runtime_error(
        "render: cannot create an OSMesa OpenGL 4.5 core context (needs Mesa's libOSMesa with "
        "llvmpipe, Debian package libosmesa6; check that GALLIUM_DRIVER is unset or llvmpipe)");
  }
  context_ = context;
  if (!OSMesaMakeCurrent(context, placeholder_, GL_UNSIGNED_BYTE, 1, 1)) {
    OSMesaDestroyContext(context);
    throw std::runtime_error("render: OSMesaMakeCurrent failed on a new context");
  }
  try {
    gl_.load(&getProc);
  } catch (...) {
    OSMesaDestroyContext(context);
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
  OSMesaContext context = static_cast<OSMesaContext>(context_);
  if (OSMesaGetCurrentContext() == context) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  OSMesaDestroyContext(context);
}

void GlContext::makeCurrent() {
  OSMesaContext context = static_cast<OSMesaContext>(context_);
  if (OSMesaGetCurrentContext() == context) return;
  if (!OSMesaMakeCurrent(context, placeholder_, GL_UNSIGNED_BYTE, 1, 1)) {
    throw std::runtime_error(
        "render: OSMesaMakeCurrent failed (is the context current on "
        "another thread?)");
  }
}

}  // namespace render
