#pragma once
// Gradient shading (transfer/shading.h) in the GL volume renderers: the uniforms of the GLSL both
// fragment programs call (render/volume/volume_shading.glsl, shadeColour) for one brick. One
// definition, so slicing and ray casting shade alike.
//
// A brick's texture holds its samples and one ghost layer where the volume continues, clamped at
// its edge. That is enough: a sample the brick owns lies in its domain [lo, hi] (per axis, in
// sample indices), so the differences read the trilinear field in [lo - 1, hi + 1], whose
// support is the samples lo - 1 ... hi + 1, exactly the stored ones. (A point up to float
// rounding beyond a face reads the edge texel, an error of the rounding times the gradient.) At
// the data set's faces there is no ghost and the texture's clamp is the reference's clamp of the
// index to the grid, so both take the same one-sided difference there. No ghost layer is added:
// bricks hold what they held. (Differences two voxels out, which would need a second ghost layer,
// left a seam of up to 25/255 on 182 pixels in tests/mpi/shading.sh bricks: the test sees one.)
#include "transfer/shading.h"
#include "transfer/transfer_function.h"
#include "render/gl/gl_api.h"
#include "render/gl/gl_program.h"
#include "render/gl/gl_context.h"
#include "render/volume/volume_brick.h"

namespace sortlast {

// The shaded variant of a fragment program (SHADING defined) has volume_shading.glsl's
//   vec3 shadeColour(vec3 c, sampler3D volume, vec3 tex_coord, vec3 dir)
// in front of its own chunks: c' of transfer/shading.h for the sample at `tex_coord` of `volume` (a
// brick texture) seen along `dir` (unit; either sign). The renderers link it as a variant of
// their program and draw with the plain one while shading is off: with the shading code in the
// one program behind a uniform switch, llvmpipe ran the unshaded frames 2-3x slower (engine,
// 512^2).
//
// Sets the shaded program's uniforms for brick `b`.
void setShadingUniforms(const GlProgram& program, const Shading& s, const VolumeBrick& b,
                        const TransferFunction& tf);

// Whether the volume programs filter the brick texture in float (FLOAT_FILTER in
// volume_filter.glsl: 8 texel fetches a value) rather than by the texture unit: on a hardware
// device (EGL's device platform), whose fixed-point filtering weights a sharp transfer function
// or the gradient magnifies, and not on llvmpipe, which filters in float already and would only
// run slower. SORTLAST_FLOAT_FILTER=1 or 0 forces it either way (tests/mpi/shading.sh checks the
// float filter on llvmpipe against llvmpipe's own; scripts/gpu-check measures both on a GPU).
// Adaptive bricks (their atlas) keep the texture unit's filter.
bool floatFilter(const GlDeviceInfo& device);

}  // namespace sortlast
