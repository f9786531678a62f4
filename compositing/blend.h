#pragma once
// Blending decoded brick images into a frame, back to front, with "over" on premultiplied RGBA8.
#include <vector>

#include "common/image.h"
#include "compositing/brick_image.h"

namespace sortlast {

// `images` in back-to-front order; each is decoded and blended over what is already in `frame`
// (which starts transparent). Throws RleError on a malformed stream or a rectangle outside the
// frame.
void blendBackToFront(const std::vector<const BrickImage*>& images, ImageRGBA8& frame);

}  // namespace sortlast
