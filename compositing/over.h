#pragma once
// The "over" operator on premultiplied colour: front over back = front + (1 - front.a) * back.
// On premultiplied colour it is associative, which is what lets sort-last compositing group
// images in any way that keeps their order.
#include <cstdint>

namespace sortlast {

inline void overFloat(const float* front, float* back_inout) {
  float k = 1.0f - front[3];
  for (int c = 0; c < 4; ++c) back_inout[c] = front[c] + k * back_inout[c];
}

// RGBA8 version, as the paper blends intermediate images: exact integer rounding of
// back * (255 - a) / 255, so results are bit-identical on every rank and machine.
inline void overRGBA8(const uint8_t* front, uint8_t* back_inout) {
  unsigned k = 255u - front[3];
  for (int c = 0; c < 4; ++c) {
    unsigned v = front[c] + (back_inout[c] * k + 127u) / 255u;
    back_inout[c] = uint8_t(v > 255u ? 255u : v);
  }
}

}  // namespace sortlast
