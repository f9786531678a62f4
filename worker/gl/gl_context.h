#pragma once
// An offscreen OpenGL 4.5 core context, made current on creation, with its entry points loaded.
// Backends: OSMesa (software) and EGL (device platform on a GPU, else surfaceless). Each backend
// lives in its own file and is the only code that includes its headers.
#include <memory>
#include <string>

#include "worker/gl/gl_api.h"

namespace sortlast {

class GlContext {
 public:
  virtual ~GlContext() = default;
  const GlApi& gl() const { return gl_; }
  // "osmesa: llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 ..." — for logs and stats.
  std::string description() const { return description_; }

 protected:
  void finishSetup(const std::string& backend_note);  // loads nothing; fills description_
  GlApi gl_;
  std::string description_;
};

// backend: "osmesa" or "egl". Throws std::runtime_error with the backend's reason on failure.
std::unique_ptr<GlContext> createGlContext(const std::string& backend);
std::unique_ptr<GlContext> createOsMesaContext();
std::unique_ptr<GlContext> createEglContext();

}  // namespace sortlast
