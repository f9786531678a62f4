#pragma once
// Blending decoded images back to front with "over" on premultiplied colour: on RGBA8 with the
// paper's rounding at every blend, or in float with one rounding at the end (what the compositing
// strategies do, so that grouping the blends differently cannot change the frame).
#include <vector>

#include "io/image.h"
#include "compositing/brick_image.h"
#include "compositing/rect_image.h"

namespace sortlast {

// `images` in back-to-front order; each is decoded and blended over what is already in `frame`
// (which starts transparent). Throws RleError on a malformed stream or a rectangle outside the
// frame. RGBA8: rounds at every blend.
void blendBackToFront(const std::vector<const BrickImage*>& images, ImageRGBA8& frame);
// The same in float; the images are RGBA8 or (glow scenes) WireFormat::Emission.
void blendBackToFront(const std::vector<const BrickImage*>& images, ImageF& frame,
                      WireFormat format = WireFormat::RGBA8);

// The same in float into one image of the rectangle the (non-empty) images cover.
RectImage blendBackToFront(const std::vector<const BrickImage*>& images,
                           WireFormat format = WireFormat::RGBA8);

// Layers in back-to-front order, each blended over the ones before it, into one image of the
// rectangle they cover. A projection format (compositing/projection_pixels.h) combines them with
// its order-free operator instead; so do the brick-image overloads above given one.
RectImage blendBackToFront(const std::vector<const RectImage*>& layers,
                           WireFormat format = WireFormat::RGBA8);

}  // namespace sortlast
