#pragma once
// The glow emitters' pass of one brick (docs/glow.md): a fragment per pixel of the brick box's
// screen rectangle integrates every emitter exactly over the ray's part inside the box, up to an
// opaque surface's t if the brick has one, and adds it (light without opacity) over the surface's
// colour. Brick shares of a ray add up to the whole box's integral; the image stays in float
// (above 1 before the final tone map), for the Emission wire format.
#include <vector>

#include "common/box.h"
#include "common/camera.h"
#include "glow/glow_field.h"
#include "render/gl/brick_output.h"
#include "render/gl/float_target.h"
#include "render/gl/gl_api.h"
#include "render/gl/gl_program.h"

namespace sortlast {

struct GlowBrickImage {
  Rect rect;
  std::vector<float> pixels;  // rect.w x rect.h premultiplied RGBA, top row first
};

class GlowRenderer {
 public:
  GlowRenderer(const GlApi& gl, int width, int height);
  ~GlowRenderer();
  GlowRenderer(const GlowRenderer&) = delete;
  GlowRenderer& operator=(const GlowRenderer&) = delete;

  void resize(int width, int height) { target_.resize(width, height); }
  // This frame's emitters (an orbit animates them), core radius and intensity.
  void setEmitters(const std::vector<GlowEmitter>& emitters, double eps, double intensity);
  // The glow inside `box` (world; the brick's part of the glow box `whole`), over `surface` (may be
  // null: any opaque surface layer with (t, normal) per pixel, t = 1e30 on a miss). The rectangle
  // covers the box and the surface.
  GlowBrickImage render(const Box3& box, const Box3& whole, const Camera& cam,
                        const SurfaceLayer* surface);
  // The same emitters for another renderer's pass over `box` (the ray caster's GLOW variant).
  GlowPass pass(const Box3& box, const Box3& whole) const {
    return {emitters_, count_, eps_, intensity_, box, whole};
  }

 private:
  const GlApi& gl_;
  FloatTarget target_;
  GlProgram program_;
  unsigned emitters_ = 0, vao_ = 0;
  std::vector<float> texels_;  // what the emitters' texture holds
  int count_ = 0;
  float eps_ = 0.01f, intensity_ = 1.0f;
};

}  // namespace sortlast
