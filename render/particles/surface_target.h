#pragma once
// The two per-pixel textures every metaball renderer ends with (render/particles/metaball_renderer.h,
// render/particles/metaball_grid_renderer.h, render/particles/metaball_slices_renderer.h): the shaded colour (RGBA32F,
// premultiplied, alpha 1 on the surface) and the surface (t, nx, ny, nz; t = 1e30 on a miss), with
// a framebuffer that draws both and the read-back of one brick's rectangle into a SurfaceBrick.
// The textures stay valid after the read-back: a volume renderer in the same brick reads them as
// its SurfaceLayer (render/gl/brick_output.h).
#include <vector>

#include "common/camera.h"
#include "render/gl/gl_context.h"

namespace sortlast {

struct SurfaceBrick;

class SurfaceTarget {
 public:
  SurfaceTarget(const GlApi& gl, int width, int height);
  ~SurfaceTarget();
  SurfaceTarget(const SurfaceTarget&) = delete;
  SurfaceTarget& operator=(const SurfaceTarget&) = delete;

  // New textures of the new size (immutable storage); nothing if the size is the same.
  void resize(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  unsigned colour() const { return colour_; }
  unsigned surface() const { return surface_; }

  // For one opaque pass writing both: binds the framebuffer with colour as attachment 0 and
  // surface as 1, both drawn, the whole image as viewport and `r` as scissor, blending off.
  // `what` names the renderer in the error thrown if the framebuffer is not complete.
  void bindForDrawing(const Rect& r, const char* what);
  // Reads `r` back: the colour into out.pixels (8 bits), and the surface into out.surface if
  // `want_surface`; sets out.rect. Leaves the framebuffer with one draw buffer and no scissor test.
  void readBack(const Rect& r, bool want_surface, SurfaceBrick& out);

 private:
  void allocate(int width, int height);
  void free();
  void attachBoth();

  const GlApi& gl_;
  int width_ = 0, height_ = 0;
  unsigned fbo_ = 0, colour_ = 0, surface_ = 0;
  std::vector<float> readback_;
};

}  // namespace sortlast
