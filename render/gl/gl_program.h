#pragma once
// Compiling and linking GLSL programs from composed sources (render/gl/shader_source.h), and the
// one owner of a linked program. Errors carry the driver's log, its locations turned into the
// .glsl files and lines they name.
#include "render/gl/gl_api.h"
#include "render/gl/shader_source.h"

namespace sortlast {

// Throw std::runtime_error: "GLSL compile error: path.glsl:LINE(COL): error: ..." (the log,
// located), or "GLSL link error (the files): log".
unsigned linkProgram(const GlApi& gl, const ShaderSource& vertex, const ShaderSource& fragment);
unsigned linkComputeProgram(const GlApi& gl, const ShaderSource& compute);

// A linked program, deleted with its owner (a renderer's member; moves, never copies).
class GlProgram {
 public:
  GlProgram() = default;
  GlProgram(const GlApi& gl, unsigned id) : gl_(&gl), id_(id) {}
  GlProgram(GlProgram&& o) noexcept : gl_(o.gl_), id_(o.id_) { o.id_ = 0; }
  GlProgram& operator=(GlProgram&& o) noexcept;
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;
  ~GlProgram();
  unsigned id() const { return id_; }
  operator unsigned() const { return id_; }

 private:
  const GlApi* gl_ = nullptr;
  unsigned id_ = 0;
};

}  // namespace sortlast
