// OSMesa backend: Mesa's off-screen software renderer (llvmpipe). OSMesa needs a colour buffer to
// make a context current; we render into our own framebuffer objects, so a tiny one suffices.
//
// libOSMesa is opened at run time (dlopen), not linked: a GPU node then needs no Mesa at all, and
// its gl* symbols, which glvnd's libraries export too, never enter the binary's symbol lookup
// (RTLD_LOCAL). Only OSMesa's own four functions are taken from it by name.
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "render/gl/gl_context.h"

namespace sortlast {

namespace {

struct OsMesaLibrary {
  decltype(&OSMesaCreateContextAttribs) create = nullptr;
  decltype(&OSMesaMakeCurrent) make_current = nullptr;
  decltype(&OSMesaGetProcAddress) get_proc = nullptr;
  decltype(&OSMesaDestroyContext) destroy = nullptr;
};

// Opened once and never closed (Mesa is not made to be unloaded).
const OsMesaLibrary& osmesa() {
  static const OsMesaLibrary lib = [] {
    void* h = nullptr;
    std::string why;
    for (const char* name : {"libOSMesa.so.8", "libOSMesa.so"}) {
      h = dlopen(name, RTLD_NOW | RTLD_LOCAL);
      if (h) break;
      const char* e = dlerror();
      why += std::string(why.empty() ? "" : "; ") + (e ? e : name);
    }
    if (!h)
      throw std::runtime_error("OSMesa: cannot load libOSMesa (" + why +
                               "); install Mesa's OSMesa (Debian: libosmesa6) or use render.backend: egl");
    OsMesaLibrary l;
    l.create = reinterpret_cast<decltype(l.create)>(dlsym(h, "OSMesaCreateContextAttribs"));
    l.make_current = reinterpret_cast<decltype(l.make_current)>(dlsym(h, "OSMesaMakeCurrent"));
    l.get_proc = reinterpret_cast<decltype(l.get_proc)>(dlsym(h, "OSMesaGetProcAddress"));
    l.destroy = reinterpret_cast<decltype(l.destroy)>(dlsym(h, "OSMesaDestroyContext"));
    if (!l.create || !l.make_current || !l.get_proc || !l.destroy)
      throw std::runtime_error("OSMesa: libOSMesa lacks OSMesaCreateContextAttribs and friends (Mesa too old?)");
    return l;
  }();
  return lib;
}

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() : buffer_(16 * 16 * 4) {
    const OsMesaLibrary& lib = osmesa();
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                           OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    ctx_ = lib.create(attribs, nullptr);
    if (!ctx_) throw std::runtime_error("OSMesa: cannot create an OpenGL 4.5 core context");
    if (!lib.make_current(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 16, 16))
      throw std::runtime_error("OSMesa: cannot make the context current");
    gl_.load([](const char* name) { return reinterpret_cast<void*>(osmesa().get_proc(name)); });
    info_.backend = "osmesa";
    finishSetup();
  }
  ~OsMesaContext() override {
    if (ctx_) osmesa().destroy(ctx_);
  }

 private:
  OSMesaContext ctx_ = nullptr;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext() { return std::make_unique<OsMesaContext>(); }

}  // namespace sortlast
