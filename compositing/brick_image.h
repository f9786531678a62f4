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
  // Instead of `rle`, where the compositor blends the image on this rank without sending it
  // (Compositor::takesLocalEmission): the brick's float pixels (rect.w * rect.h premultiplied RGBA,
  // row 0 first), rounded through the Emission format's half floats as they are blended, so the
  // frame holds the same bits as from their encoding. Never packed or sent.
  std::vector<float> emission;
};

// Wire format: six int32 (brick id, x, y, w, h, byte count) then the RLE bytes.
std::vector<uint8_t> packBrickImage(const BrickImage& b);
BrickImage unpackBrickImage(const std::vector<uint8_t>& bytes);  // throws RleError if malformed

}  // namespace sortlast
