#pragma once
// What a worker sends for one brick: the screen rectangle its projection covers and the RLE stream
// of that rectangle's RGBA8 pixels (row 0 of the rectangle first).
#include <cstdint>
#include <vector>

#include "common/camera.h"

namespace sortlast {

struct BrickImage {
  int brick_id = -1;
  Rect rect;                  // empty: the brick is invisible (skipped or off screen)
  std::vector<uint8_t> rle;   // encodes rect.w * rect.h pixels
};

// Wire format: six int32 (brick id, x, y, w, h, byte count) then the RLE bytes.
std::vector<uint8_t> packBrickImage(const BrickImage& b);
BrickImage unpackBrickImage(const std::vector<uint8_t>& bytes);  // throws RleError if malformed

}  // namespace sortlast
