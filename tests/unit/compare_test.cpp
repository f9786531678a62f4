// `sortlast compare --float` (app/compare.h): tolerances, non-finite values, shape checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.h"
#include "app/compare.h"

using namespace sortlast;

namespace {
ImageChannels image(int w, int h, int c, float v) {
  ImageChannels img;
  img.width = w;
  img.height = h;
  img.channels = c;
  img.px.assign(size_t(w) * h * c, v);
  return img;
}
}  // namespace

TEST(CompareFloat, IdenticalImagesHaveNoDifference) {
  ImageChannels a = image(3, 2, 4, 0.25f);
  FloatDifference d = compareFloatImages(a, a, 0.0, 0.0);
  EXPECT_EQ(d.values_differing, 0);
  EXPECT_EQ(d.values_over, 0);
  EXPECT_EQ(d.max_abs, 0.0);
}

TEST(CompareFloat, OneUlpIsADifferenceAtZeroTolerance) {
  ImageChannels a = image(3, 2, 3, 0.5f), b = a;
  b.px[3 * (1 * 3 + 2) + 1] = std::nextafter(0.5f, 1.0f);  // pixel (2, 1), channel 1
  FloatDifference d = compareFloatImages(a, b, 0.0, 0.0);
  EXPECT_EQ(d.values_differing, 1);
  EXPECT_EQ(d.values_over, 1);
  EXPECT_EQ(d.worst_x, 2);
  EXPECT_EQ(d.worst_y, 1);
  EXPECT_EQ(d.worst_channel, 1);
  EXPECT_EQ(compareFloatImages(a, b, 1e-6, 0.0).values_over, 0);   // within the absolute bound
  EXPECT_EQ(compareFloatImages(a, b, 0.0, 1e-6).values_over, 0);   // within the relative bound
}

TEST(CompareFloat, NonFiniteValuesCompareByKind) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::nanf("");
  ImageChannels a = image(2, 1, 1, inf), b = a;
  EXPECT_EQ(compareFloatImages(a, b, 0.0, 0.0).values_differing, 0);  // inf == inf (a surface miss)
  a.px[0] = b.px[0] = nan;
  EXPECT_EQ(compareFloatImages(a, b, 0.0, 0.0).values_differing, 0);  // NaN against NaN: the same
  b.px[1] = 1e30f;
  FloatDifference d = compareFloatImages(a, b, 1e9, 1.0);            // no tolerance covers inf
  EXPECT_EQ(d.values_over, 1);
  EXPECT_TRUE(std::isinf(d.max_abs));
  b.px[0] = 0.0f;
  EXPECT_EQ(compareFloatImages(a, b, 1e9, 1.0).values_over, 2);      // NaN against a number
}

TEST(CompareFloat, ShapesMustMatch) {
  EXPECT_THROW(compareFloatImages(image(2, 2, 4, 0), image(2, 2, 3, 0), 0, 0), InputError);
  EXPECT_THROW(compareFloatImages(image(2, 2, 4, 0), image(2, 3, 4, 0), 0, 0), InputError);
}

namespace {
ImageRGBA8 grey(int w, int h, uint8_t v) {
  ImageRGBA8 img(w, h);
  std::fill(img.px.begin(), img.px.end(), v);
  return img;
}
}  // namespace

// The accuracy goal's second bound: the pixels whose largest channel difference exceeds 4/255.
TEST(CompareRGBA8, Over4CountsPixelsByTheirLargestChannelDifference) {
  ImageRGBA8 a = grey(10, 10, 100), b = a;
  ImageDifference d = compareImages(a, b);
  EXPECT_EQ(d.over4, 0);
  EXPECT_EQ(d.over4_share, 0.0);
  b.px[4 * 3 + 0] = 104;                         // pixel 3: 4/255 off, within the bound
  b.px[4 * 7 + 1] = 105;                         // pixel 7: 5/255 off in green
  b.px[4 * 7 + 2] = 110;                         // ... and 10/255 in blue: still one pixel
  b.px[4 * 42 + 2] = 95;                         // pixel 42: 5/255 off, the other way
  d = compareImages(a, b);
  EXPECT_EQ(d.over4, 2);
  EXPECT_DOUBLE_EQ(d.over4_share, 0.02);
  EXPECT_EQ(d.max_diff, 10);
  EXPECT_EQ(d.over4, countPixelsOver(a, b, 4));  // agrees with --max-diff 4's count
}
