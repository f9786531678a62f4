#pragma once
// Gradient shading (common/shading.h) in the GL volume renderers: the GLSL both fragment programs
// call, and its uniforms for one brick. One definition, so slicing and ray casting shade alike.
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
#include <string>

#include "common/shading.h"
#include "common/transfer_function.h"
#include "worker/gl/gl_api.h"
#include "worker/volume/volume_brick.h"

namespace sortlast {

// The shaded variant of a fragment program: `fragment_src` with "#define SHADING 1", the shading
// uniforms and
//   vec3 shadeColour(vec3 c, sampler3D volume, vec3 tex_coord, vec3 dir)
// inserted after its #version line: c' of common/shading.h for the sample at `tex_coord` of
// `volume` (a brick texture) seen along `dir` (unit; either sign). The renderers link it as a
// second program and draw with the plain one while shading is off: with the shading code in the
// one program behind a uniform switch, llvmpipe ran the unshaded frames 2-3x slower (engine,
// 512^2). Throws std::logic_error if the source does not start with "#version 450 core".
std::string withShading(const char* fragment_src);

// Sets the shaded program's uniforms for brick `b`.
void setShadingUniforms(const GlApi& gl, unsigned program, const Shading& s, const VolumeBrick& b,
                        const TransferFunction& tf);

}  // namespace sortlast
