#include "render/gl/rgba8_pass.h"

#include <stdexcept>
#include <string>

#include "render/gl/glsl_files.h"

namespace sortlast {

Rgba8Pass::Rgba8Pass(const GlApi& gl)
    : gl_(gl),
      program_(gl, linkProgram(gl, ShaderSource().add(glsl::fullscreen_vert), ShaderSource().add(glsl::rgba8_frag))) {
  gl_.GenFramebuffers(1, &fbo_);
  gl_.GenTextures(1, &target_);
  gl_.GenVertexArrays(1, &vao_);  // core profile: a draw needs a vertex array, even an empty one
}

Rgba8Pass::~Rgba8Pass() {
  gl_.DeleteVertexArrays(1, &vao_);
  gl_.DeleteFramebuffers(1, &fbo_);
  gl_.DeleteTextures(1, &target_);
}

void Rgba8Pass::run(unsigned source, int width, int height, const Rect& r) {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  if (width != width_ || height != height_) {
    gl_.BindTexture(GL_TEXTURE_2D, target_);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8UI, width, height, 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, nullptr);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target_, 0);
    if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("OpenGL: RGBA8UI conversion target of " + std::to_string(width) + " x " +
                               std::to_string(height) + " is not complete");
    width_ = width;
    height_ = height;
  }
  gl_.Viewport(0, 0, width, height);
  gl_.Enable(GL_SCISSOR_TEST);
  gl_.Scissor(r.x, r.y, r.w, r.h);
  gl_.Disable(GL_BLEND);
  gl_.UseProgram(program_);
  program_.set("u_source", 0);
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindTexture(GL_TEXTURE_2D, source);
  gl_.BindVertexArray(vao_);
  gl_.DrawArrays(GL_TRIANGLES, 0, 3);
  gl_.Disable(GL_SCISSOR_TEST);
  gl_.check("RGBA8 conversion pass");
}

}  // namespace sortlast
