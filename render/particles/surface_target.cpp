#include "render/particles/surface_target.h"

#include <stdexcept>
#include <string>

#include "render/particles/particle_renderer.h"

namespace sortlast {

namespace {

unsigned makeTarget(const GlApi& gl, int w, int h) {
  unsigned t = 0;
  gl.GenTextures(1, &t);
  gl.BindTexture(GL_TEXTURE_2D, t);
  gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, w, h);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

const GLenum kBoth[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};

}  // namespace

SurfaceTarget::SurfaceTarget(const GlApi& gl, int width, int height) : gl_(gl) {
  allocate(width, height);
  gl_.GenFramebuffers(1, &fbo_);
}

SurfaceTarget::~SurfaceTarget() {
  free();
  gl_.DeleteFramebuffers(1, &fbo_);
}

void SurfaceTarget::allocate(int width, int height) {
  width_ = width;
  height_ = height;
  colour_ = makeTarget(gl_, width, height);
  surface_ = makeTarget(gl_, width, height);
}

void SurfaceTarget::free() {
  for (unsigned t : {colour_, surface_}) gl_.DeleteTextures(1, &t);
}

void SurfaceTarget::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  free();
  allocate(width, height);
}

void SurfaceTarget::attachBoth() {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_, 0);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, surface_, 0);
}

void SurfaceTarget::bindForDrawing(const Rect& r, const char* what) {
  attachBoth();
  gl_.DrawBuffers(2, kBoth);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error(std::string("OpenGL: ") + what + " framebuffer is not complete");
  gl_.Viewport(0, 0, width_, height_);
  gl_.Enable(GL_SCISSOR_TEST);
  gl_.Scissor(r.x, r.y, r.w, r.h);
  gl_.Disable(GL_BLEND);
  gl_.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void SurfaceTarget::readBack(const Rect& r, bool want_surface, SurfaceBrick& out) {
  // The billboard renderer draws through a framebuffer of its own: attach here too (for the grid
  // and slices renderers it is what bindForDrawing left).
  attachBoth();
  readback_.resize(size_t(r.area()) * 4);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl_.ReadPixels(r.x, r.y, r.w, r.h, GL_RGBA, GL_FLOAT, readback_.data());
  out.rect = r;
  out.pixels = ImageRGBA8(r.w, r.h);
  toRGBA8(readback_.data(), out.pixels.px.data(), size_t(r.area()));  // on the pixel threads
  if (want_surface) {
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT1);
    out.surface.resize(size_t(r.area()) * 4);
    gl_.ReadPixels(r.x, r.y, r.w, r.h, GL_RGBA, GL_FLOAT, out.surface.data());
  }
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl_.DrawBuffers(1, kBoth);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, 0, 0);
  gl_.Disable(GL_SCISSOR_TEST);
}

}  // namespace sortlast
