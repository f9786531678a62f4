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
#include <string>
#include <vector>

#include "io/anisotropic_kernels.h"
#include "common/box.h"
#include "common/camera.h"
#include "io/image.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"
#include "render/particles/surface_target.h"

namespace sortlast {

struct MetaballSettings {
  double h = 0.61;              // influence radius (world units)
  double threshold = 0.765625;  // T
  double step = 0.61 / 8;       // sample step w (world units)
  int max_samples = 96;         // cap on samples per pixel and brick
  int samples_per_pass = 8;     // window length: 4 (the paper, one RGBA target) or 8 (two)
  int refine_iterations = 3;
  bool cull = true;
  glm::dvec3 colour{0.85, 0.9, 1.0};
  // billboards (this renderer, the paper's) | grid (render/particles/metaball_grid_renderer.h) | slices
  // (render/particles/metaball_slices_renderer.h); read by the caller that picks the renderer
  // (render/brick_renderer.cpp)
  std::string method = "grid";
  // particles.smoothing: anisotropic (grid method only): kernels computed per brick
  // (io/anisotropic_kernels.h) from the brick's particles and ghosts.
  bool anisotropic = false;
  AnisotropicParams anisotropic_params;
  double slice_spacing = 0.25;  // slices: lattice spacing in units of h
};

struct SurfaceBrick {
  Rect rect;                    // empty: no particle can show in this brick
  ImageRGBA8 pixels;            // rect.w x rect.h, alpha 1 on the surface, 0 elsewhere
  std::vector<float> surface;   // if asked for: rect.w x rect.h x (t, nx, ny, nz); t = 1e30 on a miss
  int rounds = 0;               // windows sampled (for stats)
};

// The uniforms every method's programs share (render/particles/metaball_common.glsl and the
// passes'): the rays of `cam` over a width x height image, h, T, the step w, the sample cap, the
// refinement passes, the colour and the brick's clip box. A program that lacks one ignores it
// (location -1).
void setRayUniforms(const GlApi& gl, unsigned program, const Camera& cam, int width, int height,
                    const MetaballSettings& s, const Box3& clip);

// What render/brick_renderer.cpp needs of a metaball renderer, whichever method draws it.
class ParticleRenderer {
 public:
  virtual ~ParticleRenderer() = default;
  virtual void resize(int width, int height) = 0;
  virtual void setSettings(const MetaballSettings& settings) = 0;
  virtual int addBrick(const Box3& clip, const std::vector<glm::vec3>& particles) = 0;
  virtual SurfaceBrick render(int handle, const Camera& cam, double near_plane, double far_plane,
                              bool want_surface = false) = 0;
  virtual unsigned surfaceTexture() const = 0;
  virtual unsigned colourTexture() const = 0;
};

class MetaballRenderer : public ParticleRenderer {
 public:
  MetaballRenderer(const GlContext& ctx, int width, int height, const MetaballSettings& settings);
  ~MetaballRenderer() override;
  MetaballRenderer(const MetaballRenderer&) = delete;
  MetaballRenderer& operator=(const MetaballRenderer&) = delete;

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

  // After render(): a texture of (t, nx, ny, nz) per pixel over the last brick's rectangle
  // (t = 1e30 where it missed), for a volume renderer to end its rays at the surface.
  unsigned surfaceTexture() const override { return target_.surface(); }
  // After render(): the shaded colour (RGBA32F, premultiplied, alpha 1 on the surface).
  unsigned colourTexture() const override { return target_.colour(); }

 private:
  struct GpuBrick {
    Box3 clip;
    Box3 bound;        // clip box cut down to where the particles' field can be non-zero
    unsigned vbo = 0;
    int count = 0;
  };
  void setCommonUniforms(unsigned program, const Camera& cam, const GpuBrick& b) const;
  void fullscreen(unsigned program);
  void buildPyramid(const Rect& r);
  void drawBillboards(unsigned program, const GpuBrick& b, const glm::mat4& vp, const Rect& r,
                      float cull_pad);
  void attach(unsigned texture, int level = 0);
  void allocateTargets(int width, int height);
  void freeTargets();

  const GlApi& gl_;
  int width_, height_, levels_;
  MetaballSettings s_;
  unsigned fbo_ = 0, vao_ = 0, empty_vao_ = 0, query_ = 0;
  unsigned state_ = 0, hit_ = 0, next_ = 0, pot_ = 0, pot2_ = 0, pyramid_ = 0;
  SurfaceTarget target_;  // the shade pass's colour and the surface (t, normal)
  // One program per pass (render/particles/metaball_*.glsl).
  GlProgram advance_, potential_, init_, window_, step_, secant_, bracket_, bracket_base_, shade_,
      reduce_;
  std::vector<GpuBrick> bricks_;
};

}  // namespace sortlast
