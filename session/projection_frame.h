#pragma once
// The final step of a projection's frame (render.blend: mip, minip, average, additive): the
// combined values turned into premultiplied RGBA through the transfer function, once, where the
// compositor makes the final pixels (CompositeOptions::colour_projection).
#include <cstddef>
#include <functional>
#include <memory>

#include "compositing/rect_image.h"
#include "scene/scene.h"
#include "scene/sections.h"
#include "transfer/transfer_function.h"

namespace sortlast {

// Whether a projection is bounded by an opaque layer: particles or subdivision surfaces in the frame.
inline bool projectionBounded(const Scene& s) { return s.particles.enabled() || !s.surfaces.empty(); }

// The wire format of a projection's partial images; RGBA8 for composite (not a projection).
// `bounded`: particles or subdivision surfaces in the frame (the formats that carry the opaque
// layer, compositing/projection_pixels.h).
WireFormat projectionFormat(VolumeBlend blend, bool bounded = false);

// Colours combined pixels in place: mip / minip (v, ., ., 1) and average (sum, ., ., count) to
// (c(v) a(v), a(v)) of v = the value or sum / count (transfer/projection_colour.h); additive sums
// clamped to [0, 1] (as the average's mean, the additive sums carry the count's place: bounded
// ones in the packed halves); an absent pixel stays transparent. `tf` is read at each call (the session
// keeps it current as requests change the transfer function). `bounded` (projectionFormat's):
// the value's colour over the opaque layer's (transfer/projection_colour.h overOpaque).
std::function<void(float*, size_t)> projectionColouring(VolumeBlend blend,
                                                        std::shared_ptr<const TransferFunction> tf,
                                                        bool bounded = false);

}  // namespace sortlast
