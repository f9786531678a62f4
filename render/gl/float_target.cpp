#include "render/gl/float_target.h"

#include <stdexcept>
#include <string>

namespace sortlast {

FloatTarget::FloatTarget(const GlApi& gl, int width, int height)
    : gl_(gl), width_(width), height_(height) {
  gl_.GenTextures(1, &colour_);
  gl_.BindTexture(GL_TEXTURE_2D, colour_);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.GenFramebuffers(1, &fbo_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_, 0);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("OpenGL: float framebuffer of " + std::to_string(width) + " x " +
                             std::to_string(height) + " is not complete");
}

void FloatTarget::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  gl_.BindTexture(GL_TEXTURE_2D, colour_);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
  width_ = width;
  height_ = height;
  gl_.check("float target resize");
}

FloatTarget::~FloatTarget() {
  gl_.DeleteFramebuffers(1, &fbo_);
  gl_.DeleteTextures(1, &colour_);
}

void FloatTarget::begin(const Rect& r, const SurfaceLayer* surface) {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.Viewport(0, 0, width_, height_);
  gl_.Enable(GL_SCISSOR_TEST);
  gl_.Scissor(r.x, r.y, r.w, r.h);
  gl_.ClearColor(0, 0, 0, 0);
  gl_.Clear(GL_COLOR_BUFFER_BIT);
  if (surface) {
    const Rect& s = surface->rect;
    gl_.CopyImageSubData(surface->colour_texture, GL_TEXTURE_2D, 0, s.x, s.y, 0, colour_,
                         GL_TEXTURE_2D, 0, s.x, s.y, 0, s.w, s.h, 1);
  }
}

void FloatTarget::finish(const Rect& r, RenderedBrick& out) {
  if (!deferred_) {
    out.pixels = finish(r);
    return;
  }
  gl_.Disable(GL_SCISSOR_TEST);
  out.unread = this;
}

PendingPixels FloatTarget::readAsync(const Rect& r) {
  if (!rgba8_) {
    rgba8_ = std::make_unique<Rgba8Pass>(gl_);
    ring_ = std::make_unique<PixelReadback>(gl_);
  }
  rgba8_->run(colour_, width_, height_, r);  // leaves its RGBA8UI target bound for reading
  return ring_->start(r, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, 4);
}

std::vector<float> FloatTarget::finishFloat(const Rect& r) {
  std::vector<float> out(size_t(r.area()) * 4);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.ReadPixels(r.x, r.y, r.w, r.h, GL_RGBA, GL_FLOAT, out.data());
  gl_.Disable(GL_SCISSOR_TEST);
  gl_.check("brick render");
  return out;
}

ImageRGBA8 FloatTarget::finish(const Rect& r) {
  // Window row y is image row y (the projection flips y), so rows come back top first. Bound
  // again: a deferred read comes after other targets may have been bound.
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  readback_.resize(size_t(r.area()) * 4);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.ReadPixels(r.x, r.y, r.w, r.h, GL_RGBA, GL_FLOAT, readback_.data());
  gl_.Disable(GL_SCISSOR_TEST);
  gl_.check("brick render");
  ImageRGBA8 out(r.w, r.h);
  toRGBA8(readback_.data(), out.px.data(), size_t(r.area()));  // on the pixel threads
  return out;
}

}  // namespace sortlast
