#pragma once
// IEEE half floats for the Emission wire format (compositing/rect_image.h), per pixel channel on
// every brick image and partial composite of a glow scene, so they are on the per-frame path.
// halfBits is glm::packHalf1x16 bit for bit (the same rounding: to nearest, ties away from zero,
// decided by the first dropped bit alone) without its calls and overflow loop: generic x86-64 has
// no F16C, and CI builds for it. tests/unit/half_test.cpp compares the two over every float bit
// pattern of a stride through the range the format stores ([-1, 65504]) and every tie.
#include <cstdint>
#include <cstring>

#include <glm/gtc/packing.hpp>

namespace sortlast {

inline uint16_t halfBits(float x) {
  uint32_t i;
  std::memcpy(&i, &x, 4);
  const uint32_t s = (i >> 16) & 0x8000u;
  const int e = int((i >> 23) & 0xffu) - (127 - 15);
  uint32_t m = i & 0x007fffffu;
  if (e <= 0) {  // a half subnormal (or zero): the implicit 1 shifted in, then rounded
    if (e < -10) return uint16_t(s);
    m = (m | 0x00800000u) >> (1 - e);
    return uint16_t(s | ((m >> 13) + ((m >> 12) & 1u)));
  }
  if (e >= 31) return glm::packHalf1x16(x);  // Inf, NaN or too large: glm's own answer
  // A normal half. Rounding up carries from the mantissa into the exponent by itself (1.11..1
  // becomes the next power of two, and 65504 and below never reach Inf).
  return uint16_t(s | (((uint32_t(e) << 10) | (m >> 13)) + ((m >> 12) & 1u)));
}

}  // namespace sortlast
