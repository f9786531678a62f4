#pragma once
// The offscreen target of the volume renderers: an RGBA32F framebuffer of the image's size, so
// many samples blend without 8-bit rounding; a brick is drawn into a scissored rectangle of it,
// over the particle surface's colour when the brick has one, and read back once as RGBA8.
#include "common/camera.h"
#include "io/image.h"
#include "render/gl/brick_output.h"
#include "render/gl/gl_api.h"
#include "render/gl/pixel_readback.h"
#include "render/gl/rgba8_pass.h"

#include <memory>

namespace sortlast {

class FloatTarget {
 public:
  // Throws std::runtime_error if the framebuffer is not complete.
  FloatTarget(const GlApi& gl, int width, int height);
  ~FloatTarget();
  FloatTarget(const FloatTarget&) = delete;
  FloatTarget& operator=(const FloatTarget&) = delete;

  // The resident session changes the image size between frames: the texture is reallocated (its
  // contents are cleared per brick anyway); nothing else depends on the size.
  void resize(int width, int height);
  int width() const { return width_; }
  unsigned colourTexture() const { return colour_; }  // RGBA32F (tests fill it directly)
  unsigned framebuffer() const { return fbo_; }
  int height() const { return height_; }

  // Binds the framebuffer, scissors to `r` and clears it to transparent; then copies the
  // surface's colour over its rectangle (which must lie inside `r`), if there is a surface.
  void begin(const Rect& r, const SurfaceLayer* surface);
  // Reads `r` back as premultiplied RGBA8 (top row first) and ends the scissor.
  ImageRGBA8 finish(const Rect& r);
  // The renderer's finish: `out.pixels` = finish(r), or, deferred, the scissor ended and
  // `out.unread` = this (the caller reads it with readAsync).
  void finish(const Rect& r, RenderedBrick& out);
  void setDeferred(bool on) { deferred_ = on; }
  // Converts `r` to RGBA8 on the GPU (Rgba8Pass, bit for bit toRGBA8's) and starts reading it
  // into the ring of pixel-buffer objects; returns at once (pixel_readback.h).
  PendingPixels readAsync(const Rect& r);
  // The same unrounded (glow scenes: light without opacity, above 1): 4 floats a pixel.
  std::vector<float> finishFloat(const Rect& r);

 private:
  const GlApi& gl_;
  int width_, height_;
  unsigned fbo_ = 0, colour_ = 0;
  std::vector<float> readback_;
  bool deferred_ = false;
  std::unique_ptr<Rgba8Pass> rgba8_;       // made on the first deferred read
  std::unique_ptr<PixelReadback> ring_;
};

}  // namespace sortlast
