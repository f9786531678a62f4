#pragma once
// The metaball ray caster of Mishima, Tanaka and Sagawa (../shared/PAPERS.md §2), in OpenGL 4.5
// core, one brick at a time. A brick holds the particles inside its clip box plus ghost copies of
// those within h of it; rays are clipped to the box, so bricks composite like volume bricks and
// the surface has no seam or double layer at brick faces.
//
// Per brick and frame:
//   1. init: each pixel's ray interval in the clip box.
//   2. repeat (one window of 8 (or the paper's 4) samples per round, until no pixel searches):
//        advance  — billboards, MIN blending: where the next window starts (eqs. 1-4);
//        window   — the window's [first, last] sample per pixel, reduced into a min/max pyramid;
//        potential— billboards, additive blending: F at the samples (eq. 7, §4.2), particles
//                   whose distance range misses their tile's window culled (§4.3);
//        step     — first sample with I = sqrt(F) - T >= 0 ends the search (eq. 8).
//   3. refine: `refine_iterations` passes of 4 probes around the secant estimate (eqs. 5-6).
//   4. shade: gradient of F at the final t; opaque premultiplied RGBA, plus t and the normal.
#include <vector>

#include "common/box.h"
#include "common/camera.h"
#include "io/image.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"
#include "render/particles/metaball_base.h"

namespace sortlast {

class MetaballRenderer : public MetaballBase {
 public:
  MetaballRenderer(const GlContext& ctx, int width, int height, const MetaballSettings& settings);
  ~MetaballRenderer() override;

  // A new image size for the next frames: the per-pixel textures are reallocated, the bricks'
  // particle buffers stay.
  void resize(int width, int height) override;
  // Settings for the next frames. The influence radius h must stay: the bricks' bounds (and the
  // ghosts their callers chose) depend on it; throws std::logic_error otherwise.
  void setSettings(const MetaballSettings& settings) override;

  // `particles`: the brick's own particles and its ghosts, in global order (the field is summed
  // in this order, so every decomposition adds the same numbers in the same order).
  int addBrick(const Box3& clip, const std::vector<glm::vec3>& particles) override;

  // [near_plane, far_plane] must hold every particle's billboard (the same for all bricks).
  SurfaceBrick render(int handle, const Camera& cam, double near_plane, double far_plane,
                      bool want_surface = false) override;

 private:
  // bound: the clip box cut down to where the particles' field can be non-zero.
  struct GpuBrick : BrickBox {
    unsigned vbo = 0;
    int count = 0;
  };
  void setCommonUniforms(const GlProgram& program, const Camera& cam, const GpuBrick& b) const;
  void fullscreen(unsigned program);
  void buildPyramid(const Rect& r);
  void drawBillboards(const GlProgram& program, const GpuBrick& b, const glm::mat4& vp,
                      const Rect& r, float cull_pad);
  void attach(unsigned texture, int level = 0);
  void allocateTargets(int width, int height);
  void freeTargets();

  int width_, height_, levels_;
  unsigned fbo_ = 0, vao_ = 0, query_ = 0;
  unsigned state_ = 0, hit_ = 0, next_ = 0, pot_ = 0, pot2_ = 0, pyramid_ = 0;
  // One program per pass (render/particles/metaball_*.glsl).
  GlProgram advance_, potential_, init_, window_, step_, secant_, bracket_, bracket_base_, shade_,
      reduce_;
  std::vector<GpuBrick> bricks_;
};

}  // namespace sortlast
