#pragma once
// The metaball ray caster as one pass per brick over a particle grid (particles.method: grid).
// The billboard method (render/particles/metaball_renderer.h, the paper's) re-rasterises every particle in
// every pass, 3 passes a round for 5-12 rounds plus refinement; on llvmpipe that is the whole
// cost. Here each brick's particles are binned into cells of edge h/2 (render/particles/metaball_grid.h) and
// one fragment pass walks each pixel's ray through the cells: it samples the same global lattice
// as the billboard method (so bricks and ranks agree), sums the field of the cell's list in
// global particle order, jumps empty cells, and refines and shades the first sign change of
// sqrt(F) - T exactly as the billboard passes do. Output: the same SurfaceBrick and textures.
#include <vector>

#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"
#include "render/particles/metaball_base.h"
#include "render/particles/metaball_grid.h"

namespace sortlast {

class MetaballGridRenderer : public MetaballBase {
 public:
  MetaballGridRenderer(const GlContext& ctx, int width, int height, const MetaballSettings& settings);

  // h must stay (the grids and the bricks' ghosts depend on it): std::logic_error otherwise.
  void setSettings(const MetaballSettings& settings) override;
  // `particles`: the brick's own particles and its ghosts, in global order. Builds the grid on
  // the CPU and uploads it.
  int addBrick(const Box3& clip, const std::vector<glm::vec3>& particles) override;
  // near_plane and far_plane are not needed (no rasterised geometry); kept for the interface.
  SurfaceBrick render(int handle, const Camera& cam, double near_plane, double far_plane,
                      bool want_surface = false) override;

 private:
  // bound: the clip box cut down to where the particles' field can be non-zero.
  struct GpuBrick : BrickBox {
    glm::vec3 lo{0.0f};
    float cell = 1.0f;
    glm::ivec3 dims{0};
    // SSBOs, kept by the base (kernels and indices, the lists' particle numbers: anisotropic)
    unsigned offsets = 0, items = 0, kernels = 0, indices = 0;
    int count = 0;
  };

  GlProgram program_;  // the ANISOTROPIC variant with anisotropic smoothing
  std::vector<GpuBrick> bricks_;
};

}  // namespace sortlast
