#include "worker/gl/gl_context.h"

#include <stdexcept>

namespace sortlast {

void GlContext::finishSetup(const std::string& backend_note) {
  auto str = [&](GLenum e) {
    const GLubyte* s = gl_.GetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  description_ = backend_note + ": " + str(GL_RENDERER) + ", OpenGL " + str(GL_VERSION);
}

std::unique_ptr<GlContext> createGlContext(const std::string& backend) {
  if (backend == "osmesa") return createOsMesaContext();
  if (backend == "egl") return createEglContext();
  throw std::runtime_error("unknown render.backend '" + backend + "'");
}

}  // namespace sortlast
