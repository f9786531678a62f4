// OSMesa backend: Mesa's off-screen software renderer (llvmpipe). OSMesa needs a colour buffer to
// make a context current; we render into our own framebuffer objects, so a tiny one suffices.
#include <GL/osmesa.h>

#include <stdexcept>
#include <vector>

#include "worker/gl/gl_context.h"

namespace sortlast {

namespace {

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() : buffer_(16 * 16 * 4) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                           OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_) throw std::runtime_error("OSMesa: cannot create an OpenGL 4.5 core context");
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 16, 16))
      throw std::runtime_error("OSMesa: cannot make the context current");
    gl_.load([](const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); });
    finishSetup("osmesa");
  }
  ~OsMesaContext() override {
    if (ctx_) OSMesaDestroyContext(ctx_);
  }

 private:
  OSMesaContext ctx_ = nullptr;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext() { return std::make_unique<OsMesaContext>(); }

}  // namespace sortlast
