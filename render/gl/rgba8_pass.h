#pragma once
// The conversion of a float brick image to RGBA8 on the GPU, before read-back: a quarter of the
// bytes cross the bus (or, on llvmpipe, the memcpy), and the rounding runs in the GPU's (or
// llvmpipe's threads') shader cores instead of one CPU core. Rounds as toRGBA8 does, bit for bit
// (rgba8.frag.glsl says why it can; tests/unit/pixel_readback_test.cpp checks every byte value).
#include "common/camera.h"
#include "render/gl/gl_api.h"
#include "render/gl/gl_program.h"

namespace sortlast {

class Rgba8Pass {
 public:
  explicit Rgba8Pass(const GlApi& gl);
  ~Rgba8Pass();
  Rgba8Pass(const Rgba8Pass&) = delete;
  Rgba8Pass& operator=(const Rgba8Pass&) = delete;

  // Converts rectangle `r` of `source` (an RGBA32F texture of width x height) into the pass's
  // RGBA8UI target (reallocated when the size changes) and leaves that target bound as the
  // framebuffer, to be read as GL_RGBA_INTEGER / GL_UNSIGNED_BYTE. Ends with the scissor off.
  void run(unsigned source, int width, int height, const Rect& r);

 private:
  const GlApi& gl_;
  GlProgram program_;
  unsigned target_ = 0, fbo_ = 0, vao_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace sortlast
