#pragma once
// The metaball surface from dynamic slices (particles.method: slices; Kanamori and Nishita, the
// third paper, ../shared/PAPERS.md §3). The other two methods sum the particles' field at every
// ray sample of every frame; this one samples the field once per brick and time step on a global
// lattice (render/particles/metaball_slices.h), and only where particles are:
//   addBrick: the coarse bit voxelization and the slots (CPU), the lists uploaded, then one
//             compute dispatch sums each slot's particles at its lattice points (the splat);
//   render:   one fragment pass; each ray samples the trilinear interpolation of the lattice at
//             the other methods' points t = k w, jumps voxels without a slot, refines the first
//             sign change of sqrt(F) - T and shades with the interpolated field's gradient.
// Output: the same SurfaceBrick and textures as the other methods, so compositing, volumes that
// end at the surface and the reference comparison work unchanged. Being a sampled field, its
// surface is less exact than theirs; tests/mpi/particles_slices.sh states by how much.
#include <vector>

#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"
#include "render/particles/metaball_base.h"
#include "io/anisotropic_kernels.h"
#include "render/particles/metaball_slices.h"

namespace sortlast {

class MetaballSlicesRenderer : public MetaballBase {
 public:
  MetaballSlicesRenderer(const GlContext& ctx, int width, int height,
                         const MetaballSettings& settings);

  // h and the slice spacing must stay (the lattices and the ghosts depend on them):
  // std::logic_error otherwise.
  void setSettings(const MetaballSettings& settings) override;
  // `particles`: the brick's own particles and its ghosts (within ParticleDesc::ghostMargin of
  // `clip`), in global order. Builds the lattice and splats it; InputError if the brick's samples
  // or lists pass what one shader storage block holds (naming particles.slice_spacing).
  int addBrick(const Box3& clip, const std::vector<glm::vec3>& particles) override;
  // near_plane and far_plane are not needed (no rasterised geometry); kept for the interface.
  SurfaceBrick render(int handle, const Camera& cam, double near_plane, double far_plane,
                      bool want_surface = false) override;

 private:
  // bound: the box of the brick's voxels, cut to the clip box.
  struct GpuBrick : BrickBox {
    glm::ivec3 voxel_lo{0}, dims{0};
    unsigned slot_of = 0, samples = 0;  // SSBOs, kept by the base
    size_t slots = 0;
  };
  // `kernels` (anisotropic smoothing): one per particle, for the splat's kernel buffer.
  void splat(GpuBrick& g, const SliceLattice& L, const std::vector<glm::vec3>& particles,
             const std::vector<ParticleKernel>* kernels);

  GlProgram program_, splat_;  // the ray pass; the splat (compute)
  std::vector<GpuBrick> bricks_;
};

}  // namespace sortlast
