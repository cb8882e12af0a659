// An OSMesa off-screen OpenGL context (Mesa's llvmpipe: GL 4.5 core profile), created once and
// reused for every frame a Renderer draws.
//
// OSMesa binds a context to the calling thread: all GL work for one context happens on one
// thread at a time (makeCurrent() before it; the Renderer does that on every call). The
// context's own colour buffer is a 1x1 placeholder: frames are drawn into framebuffer objects.
#pragma once

#include <string>

#include "render/gl_api.h"

namespace render {

// Whether libOSMesa is in the process yet: it is opened by the first GlContext, never at start.
bool osMesaLoaded();

class GlContext {
 public:
  // Opens libOSMesa the first time. Throws std::runtime_error with a one-line reason when the
  // library cannot be loaded or no GL 4.5 core context can be made.
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes this context current on the calling thread (a no-op when it already is).
  void makeCurrent();
  const GlApi& gl() const { return gl_; }
  // glGetString(GL_VERSION) and GL_RENDERER, for logs: "4.5 (Core Profile) Mesa 22.3.6".
  const std::string& version() const { return version_; }
  const std::string& rendererName() const { return renderer_; }

 private:
  void* context_ = nullptr;  // OSMesaContext; osmesa.h stays out of our headers
  unsigned char placeholder_[4] = {};
  GlApi gl_;
  std::string version_;
  std::string renderer_;
};

}  // namespace render
