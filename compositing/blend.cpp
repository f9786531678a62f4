#include "compositing/blend.h"

#include <string>

#include "compositing/over.h"
#include "compositing/rle.h"

namespace sortlast {

void blendBackToFront(const std::vector<const BrickImage*>& images, ImageRGBA8& frame) {
  std::vector<uint8_t> pixels;
  for (const BrickImage* b : images) {
    const Rect& r = b->rect;
    if (r.empty()) continue;
    if (r.x < 0 || r.y < 0 || r.x + r.w > frame.width || r.y + r.h > frame.height)
      throw RleError("brick " + std::to_string(b->brick_id) + ": rectangle outside the frame");
    pixels.resize(size_t(r.area()) * 4);
    rleDecode(b->rle, size_t(r.area()), pixels);
    for (int y = 0; y < r.h; ++y) {
      const uint8_t* src = &pixels[size_t(y) * r.w * 4];
      uint8_t* dst = frame.at(r.x, r.y + y);
      for (int x = 0; x < r.w; ++x)
        if (src[4 * x + 3] != 0) overRGBA8(src + 4 * x, dst + 4 * x);
    }
  }
}

}  // namespace sortlast
