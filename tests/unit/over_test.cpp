// The "over" operator (compositing/over.h) and blending brick images into a frame
// (compositing/blend.h).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include "io/image.h"
#include "compositing/blend.h"
#include "compositing/brick_image.h"
#include "compositing/over.h"
#include "compositing/rle.h"

namespace sortlast {
namespace {

using PxF = std::array<float, 4>;
using Px8 = std::array<uint8_t, 4>;

PxF randomPremultF(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  PxF p;
  p[3] = u(rng);
  for (int c = 0; c < 3; ++c) p[c] = u(rng) * p[3];
  return p;
}

Px8 randomPremult8(std::mt19937& rng) {
  Px8 p;
  int kind = int(rng() % 8);
  p[3] = kind == 0 ? 0 : kind == 1 ? 255 : uint8_t(rng() % 256);
  for (int c = 0; c < 3; ++c) p[c] = uint8_t(rng() % (p[3] + 1));
  return p;
}

PxF overF(const PxF& front, PxF back) {
  overFloat(front.data(), back.data());
  return back;
}
Px8 over8(const Px8& front, Px8 back) {
  overRGBA8(front.data(), back.data());
  return back;
}

TEST(Over, FloatMatchesDefinition) {
  PxF front = {0.1f, 0.2f, 0.3f, 0.4f}, back = {0.5f, 0.25f, 0.125f, 0.8f};
  PxF r = overF(front, back);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(r[c], front[c] + 0.6f * back[c], 1e-6f) << "channel " << c;
}

TEST(Over, FloatIsAssociative) {
  std::mt19937 rng(42);
  for (int i = 0; i < 20000; ++i) {
    PxF a = randomPremultF(rng), b = randomPremultF(rng), c = randomPremultF(rng);
    PxF left = overF(overF(a, b), c), right = overF(a, overF(b, c));
    for (int ch = 0; ch < 4; ++ch) ASSERT_NEAR(left[ch], right[ch], 1e-5f) << "sample " << i << " channel " << ch;
  }
}

TEST(Over, RGBA8MatchesDefinition) {
  Px8 front = {40, 60, 80, 100}, back = {200, 100, 50, 250};
  Px8 r = over8(front, back);
  for (int c = 0; c < 4; ++c) {
    double want = front[c] + back[c] * (255.0 - front[3]) / 255.0;
    EXPECT_LE(std::abs(r[c] - want), 0.5 + 1e-9) << "channel " << c;
  }
}

TEST(Over, RGBA8IsAssociativeWithinRounding) {
  std::mt19937 rng(43);
  for (int i = 0; i < 200000; ++i) {
    Px8 a = randomPremult8(rng), b = randomPremult8(rng), c = randomPremult8(rng);
    Px8 left = over8(over8(a, b), c), right = over8(a, over8(b, c));
    for (int ch = 0; ch < 4; ++ch)
      ASSERT_LE(std::abs(int(left[ch]) - int(right[ch])), 2) << "sample " << i << " channel " << ch;
    // The result is still a valid premultiplied pixel.
    for (int ch = 0; ch < 3; ++ch) ASSERT_LE(left[ch], left[3]);
  }
}

TEST(Over, TransparentFrontLeavesBackUnchanged) {
  std::mt19937 rng(44);
  for (int i = 0; i < 10000; ++i) {
    Px8 b8 = randomPremult8(rng);
    EXPECT_EQ(over8({0, 0, 0, 0}, b8), b8);
    PxF bf = randomPremultF(rng);
    EXPECT_EQ(overF({0, 0, 0, 0}, bf), bf);
  }
}

TEST(Over, OpaqueFrontReplacesBack) {
  std::mt19937 rng(45);
  for (int i = 0; i < 10000; ++i) {
    Px8 f8 = randomPremult8(rng), b8 = randomPremult8(rng);
    f8[3] = 255;
    EXPECT_EQ(over8(f8, b8), f8);
    PxF ff = randomPremultF(rng), bf = randomPremultF(rng);
    ff[3] = 1.0f;
    EXPECT_EQ(overF(ff, bf), ff);
  }
}

// A brick image of random premultiplied pixels (with transparent stretches) in `rect`.
BrickImage randomBrickImage(int id, Rect rect, std::mt19937& rng, std::vector<uint8_t>& pixels) {
  pixels.assign(size_t(rect.area()) * 4, 0);
  for (size_t i = 0; i < size_t(rect.area()); ++i) {
    if (rng() % 3 == 0) continue;  // transparent
    Px8 p = randomPremult8(rng);
    std::copy(p.begin(), p.end(), pixels.begin() + 4 * i);
  }
  BrickImage b;
  b.brick_id = id;
  b.rect = rect;
  b.rle = rleEncode(pixels);
  return b;
}

TEST(Blend, TwoBrickImagesMatchManualOver) {
  std::mt19937 rng(46);
  const int W = 23, H = 17;
  std::vector<uint8_t> back_px, front_px;
  Rect back_rect{2, 1, 15, 12}, front_rect{8, 5, 15, 12};  // overlapping, front touches the corner
  BrickImage back = randomBrickImage(3, back_rect, rng, back_px);
  BrickImage front = randomBrickImage(5, front_rect, rng, front_px);

  ImageRGBA8 frame(W, H);
  blendBackToFront({&back, &front}, frame);

  ImageRGBA8 want(W, H);
  for (int y = 0; y < back_rect.h; ++y)
    for (int x = 0; x < back_rect.w; ++x)
      overRGBA8(&back_px[4 * (size_t(y) * back_rect.w + x)], want.at(back_rect.x + x, back_rect.y + y));
  for (int y = 0; y < front_rect.h; ++y)
    for (int x = 0; x < front_rect.w; ++x)
      overRGBA8(&front_px[4 * (size_t(y) * front_rect.w + x)], want.at(front_rect.x + x, front_rect.y + y));
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(frame.at(x, y)[c], want.at(x, y)[c]) << "pixel " << x << "," << y << " channel " << c;

  // Order matters: the other order gives a different frame where both are partly visible.
  ImageRGBA8 swapped(W, H);
  blendBackToFront({&front, &back}, swapped);
  EXPECT_NE(swapped.px, frame.px);
}

TEST(Blend, EmptyRectIsSkipped) {
  BrickImage empty;
  empty.brick_id = 1;
  empty.rect = {100, 100, 0, 0};  // outside, but empty: nothing to do
  ImageRGBA8 frame(4, 4);
  EXPECT_NO_THROW(blendBackToFront({&empty}, frame));
  EXPECT_EQ(frame.px, std::vector<uint8_t>(64, 0));
}

TEST(Blend, RectOutsideFrameThrows) {
  std::mt19937 rng(47);
  const int W = 10, H = 8;
  for (Rect r : {Rect{-1, 0, 3, 3}, Rect{0, -1, 3, 3}, Rect{8, 0, 3, 3}, Rect{0, 6, 3, 3},
                 Rect{0, 0, 11, 8}, Rect{0, 0, 10, 9}}) {
    std::vector<uint8_t> px;
    BrickImage b = randomBrickImage(0, r, rng, px);
    ImageRGBA8 frame(W, H);
    EXPECT_THROW(blendBackToFront({&b}, frame), RleError)
        << "rect " << r.x << "," << r.y << " " << r.w << "x" << r.h;
  }
  // The largest rectangle that fits is accepted.
  std::vector<uint8_t> px;
  BrickImage full = randomBrickImage(0, Rect{0, 0, W, H}, rng, px);
  ImageRGBA8 frame(W, H);
  EXPECT_NO_THROW(blendBackToFront({&full}, frame));
}

TEST(Blend, MalformedStreamThrows) {
  BrickImage b;
  b.rect = {0, 0, 2, 2};
  b.rle = {5, 0, 0, 0};  // a run of 5 in a 4-pixel rectangle
  ImageRGBA8 frame(4, 4);
  EXPECT_THROW(blendBackToFront({&b}, frame), RleError);
}

}  // namespace
}  // namespace sortlast
