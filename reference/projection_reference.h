#pragma once
// The CPU reference of the projection blend modes (render.blend: mip, minip, average, additive) in
// double precision, for `sortlast reference` and `render --psnr` (reference/frame_reference.h).
// Each ray's part inside the volume box is cut into n = ceil(length / step) equal steps and
// sampled at their midpoints (the emission-absorption reference's samples, reference.h):
//   mip / minip: the largest / smallest sample; average: their mean (NaN samples, a stencil
//   touching a missing voxel, are not counted); additive: the sum of c(v) a and of a,
//   a = 1 - exp(-tau(v) h), h the step (no absorption).
// With `exact` (mip / minip, render.mip_exact): the exact extremum of the trilinear field along
// the ray, walking the volume's cells; in a cell the field on the ray is a cubic in t whose
// extremum lies at an end or a root of its derivative (closed form), as the GL ray caster's
// MIP_EXACT variant computes in float (render/volume/raycast_projection.frag.glsl).
#include "common/camera.h"
#include "io/image.h"
#include "io/surface_image.h"
#include "reference/reference.h"
#include "scene/sections.h"
#include "transfer/transfer_function.h"

namespace sortlast {

// The projected pixels before colouring: (v, 0, 0, 1) for mip / minip, (mean, 0, 0, 1) for
// average, (sum c a, sum a) for additive; zero where the ray takes no sample. `stop` (optional, the
// camera's size): the opaque layer (particles and subdivision surfaces, reference/frame_reference.h);
// each ray's span ends at its t, so only samples in front of the first opaque hit count.
ImageF projectReference(const WholeVolume& vol, const TransferFunction& tf, const Camera& cam,
                        double step, int threads, VolumeBlend blend, bool exact,
                        const SurfaceImage* stop = nullptr);

// The frame: projectReference's values coloured (transfer/projection_colour.h), over the opaque
// layer's colour `stop_colour` where `stop` is hit (both or neither; throws InputError on a size
// mismatch).
ImageF renderProjectionReference(const WholeVolume& vol, const TransferFunction& tf, const Camera& cam,
                                 double step, int threads, VolumeBlend blend, bool exact,
                                 const SurfaceImage* stop = nullptr, const ImageF* stop_colour = nullptr);

// The exact extremum (max if `largest`, else min) of the trilinear field of `vol` along
// o + t d, t in [t0, t1] (world units): NaN if every cell the segment crosses touches a NaN.
double exactExtremum(const WholeVolume& vol, const glm::dvec3& o, const glm::dvec3& d, double t0,
                     double t1, bool largest);

}  // namespace sortlast
