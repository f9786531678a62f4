#pragma once
// The ray caster's isosurface variant (ISOSURFACE: render/volume/raycast_isosurface.frag.glsl):
// its uniforms for one brick, and which blocks it may jump.
#include <vector>

#include "common/box.h"
#include "render/gl/gl_program.h"
#include "render/volume/volume_brick.h"
#include "transfer/isosurface.h"
#include "transfer/shading.h"

namespace sortlast {

// Sets u_iso_* (values, colours and opacities, the shading coefficients, 1 / spacing) and the
// whole volume's box `volume` (u_vol_lo / u_vol_hi) for brick `b`.
void setIsosurfaceUniforms(const GlProgram& program, const std::vector<Isovalue>& isovalues,
                           const Shading& shading, const VolumeBrick& b, const Box3& volume);

// Whether a block whose values, grown by one sample, lie in [lo, hi] can hold a crossing: some
// isovalue lies in [lo, hi]. Every interval a block owns (its samples', each from the sample
// before, up to one step <= 1 voxel outside it) reads the field inside the block grown by one
// voxel, whose values lie in that range, so a block without an isovalue in it has no crossing
// and is jumped exactly.
bool isoVisible(const std::vector<Isovalue>& isovalues, float lo, float hi);

}  // namespace sortlast
