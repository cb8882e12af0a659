#include "render/gl_api.h"

#include <stdexcept>
#include <string>

namespace render {

void GlApi::load(GetProc getProc) {
  // A function pointer cast through void (*)() is the documented way back from a generic
  // GetProcAddress result (GCC's -Wcast-function-type exempts that type).
#define RENDER_GL_LOAD(type, name)                                          \
  name = reinterpret_cast<type>(getProc("gl" #name));                       \
  if (name == nullptr) {                                                    \
    throw std::runtime_error("render: OpenGL entry point gl" #name          \
                             " is not available from "                      \
                             "OSMesa (a GL 4.5 core context is required)"); \
  }
  RENDER_GL_FUNCTIONS(RENDER_GL_LOAD)
#undef RENDER_GL_LOAD
}

}  // namespace render
