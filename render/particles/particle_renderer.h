#pragma once
// What render/brick_renderer.cpp needs of a metaball renderer, whichever method draws it
// (particles.method: billboards, render/particles/metaball_renderer.h; grid,
// render/particles/metaball_grid_renderer.h; slices, render/particles/metaball_slices_renderer.h):
// the settings all three take, the brick image and surface they return, and the interface.
#include <string>
#include <vector>

#include "common/box.h"
#include "common/camera.h"
#include "io/anisotropic_kernels.h"
#include "io/particles.h"
#include "io/image.h"

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
  // billboards (render/particles/metaball_renderer.h, the paper's) | grid
  // (render/particles/metaball_grid_renderer.h) | slices (render/particles/metaball_slices_renderer.h);
  // read by the caller that picks the renderer (render/brick_renderer.cpp)
  ParticleMethod method = ParticleMethod::kGrid;
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

// The calls every method answers.
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

}  // namespace sortlast
