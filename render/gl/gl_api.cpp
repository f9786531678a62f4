#include "render/gl/gl_api.h"

#include <stdexcept>
#include <string>

namespace sortlast {

void GlApi::load(const std::function<void*(const char*)>& get_proc) {
#define SORTLAST_GL_LOAD(name, type)                                          \
  name = reinterpret_cast<type>(get_proc("gl" #name));                        \
  if (!name) throw std::runtime_error("OpenGL entry point gl" #name " not found");
  SORTLAST_GL_FUNCTIONS(SORTLAST_GL_LOAD)
#undef SORTLAST_GL_LOAD
}

void GlApi::check(const char* what) const {
  GLenum e = GetError();
  if (e != GL_NO_ERROR) throw std::runtime_error(std::string("OpenGL error 0x") +
                                                 [&] { char b[16]; snprintf(b, sizeof b, "%x", e); return std::string(b); }() +
                                                 " after " + what);
}

}  // namespace sortlast
