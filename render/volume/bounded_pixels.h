#pragma once
// 3D-texture slicing's projections bounded by an opaque layer (particles or subdivision surfaces
// in the frame): the slices blend order-free (GL_MAX, GL_FUNC_ADD) into the unbounded partial
// pixels, the fragments behind the layer's t already discarded (slicing.frag.glsl), so only the
// layer's colour is missing. It is added here, on the read-back pixels, in the bounded formats
// the ray caster writes (compositing/projection_pixels.h, raycast_projection.frag.glsl
// projectionPixel): one conversion, so both methods composite alike.
#include <vector>

#include "scene/sections.h"

namespace sortlast {

// `px`: a projection's unbounded float pixels (mip / minip (v, 0, 0, 1), average (sum, 0, 0,
// count), additive (c a, a) sums; all zero: no sample) turned into the bounded format of `blend`.
// `layer` (optional, as many pixels): the opaque layer's premultiplied colour, alpha 1 where it
// is hit (what FloatTarget::begin copies from a SurfaceLayer), 0 elsewhere.
void toBoundedPixels(VolumeBlend blend, std::vector<float>& px, const std::vector<float>* layer);

}  // namespace sortlast
