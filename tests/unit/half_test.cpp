// halfBits (compositing/half.h) against glm::packHalf1x16, which it replaces on the Emission
// wire format's per-pixel path: it must give the same bits, or glow frames would change.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "compositing/half.h"

namespace sortlast {
namespace {

float fromBits(uint32_t i) {
  float x;
  std::memcpy(&x, &i, 4);
  return x;
}

// A stride through every float bit pattern of [+0, 65504] and [-0, -1] (what toEmission16 feeds
// it: clamped colour and -T); the stride is odd, so every mantissa bit and rounding case recurs.
TEST(Half, MatchesGlmOverTheStoredRange) {
  const uint32_t ends[2][2] = {{0x00000000u, 0x477fe000u}, {0x80000000u, 0xbf800000u}};
  size_t checked = 0;
  for (const auto& r : ends)
    for (uint64_t i = r[0]; i <= r[1]; i += 61, ++checked) {
      const float x = fromBits(uint32_t(i));
      ASSERT_EQ(halfBits(x), glm::packHalf1x16(x)) << std::hexfloat << x;
    }
  EXPECT_GT(checked, 10000000u);
}

// Every tie (the float halfway between two neighbouring halves) and its float neighbours, where
// a rounding rule that differs from glm's (ties to even, say) would show.
TEST(Half, MatchesGlmAtEveryTie) {
  for (uint32_t h = 0; h < 0x7bff; ++h) {
    const float mid = 0.5f * (glm::unpackHalf1x16(uint16_t(h)) + glm::unpackHalf1x16(uint16_t(h + 1)));
    for (float x : {mid, std::nextafter(mid, 0.0f), std::nextafter(mid, 1e9f)})
      for (float y : {x, -x}) ASSERT_EQ(halfBits(y), glm::packHalf1x16(y)) << std::hexfloat << y;
  }
}

TEST(Half, NonFiniteAndTooLargeAsGlm) {
  for (float x : {INFINITY, -INFINITY, NAN, 65520.0f, 1e9f, -70000.0f})
    EXPECT_EQ(halfBits(x), glm::packHalf1x16(x)) << x;
}

}  // namespace
}  // namespace sortlast
