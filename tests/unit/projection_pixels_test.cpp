// The projection blend modes' partial images (compositing/projection_pixels.h): their wire
// formats round-trip (value formats bit for bit, Additive within half rounding), absent pixels
// become runs, the operators are order-free, and radix-k's groupings give the same frame as
// combining every brick image at once. The bounded formats (every projection with an opaque layer)
// round-trip exactly, and their over-like operator gives one result for every grouping that keeps
// the visibility order (and another for the reverse order), in radix-k too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>
#include <thread>

#include "compositing/blend.h"
#include "compositing/projection_pixels.h"
#include "compositing/radix_k.h"
#include "compositing/rle.h"
#include "thread_transport.h"

namespace sortlast {
namespace {

constexpr WireFormat kFormats[] = {WireFormat::ValueMax, WireFormat::ValueMin, WireFormat::ValueSum,
                                   WireFormat::Additive};

// A random present pixel of format f (about one in three absent).
void randomPixel(WireFormat f, std::mt19937& rng, float* p) {
  std::uniform_real_distribution<float> u(-3.0f, 5.0f), a(0.0f, 1.0f);
  for (int c = 0; c < 4; ++c) p[c] = 0.0f;
  if (rng() % 3 == 0) return;
  if (f == WireFormat::ValueMax || f == WireFormat::ValueMin) {
    p[0] = u(rng);
    p[3] = 1.0f;
  } else if (f == WireFormat::ValueSum) {
    const int n = 1 + int(rng() % 400);
    p[0] = u(rng) * float(n);
    p[3] = float(n);
  } else {
    p[3] = a(rng) * 3.0f;
    for (int c = 0; c < 3; ++c) p[c] = a(rng) * p[3];
  }
}

TEST(ProjectionPixels, WireRoundTripAndRuns) {
  std::mt19937 rng(7);
  for (WireFormat f : kFormats) {
    RectImage img(Rect{2, 3, 40, 5});
    for (size_t i = 0; i < img.px.size(); i += 4) randomPixel(f, rng, &img.px[i]);
    // A long absent stretch: one run marker.
    for (int x = 2; x < 42; ++x) std::fill_n(img.at(x, 5), 4, 0.0f);
    BrickImage b = encodePart(img, img.rect, 1, f);
    size_t present = 0;
    for (size_t i = 0; i < img.px.size(); i += 4) present += projectedPresent(f, &img.px[i]);
    EXPECT_LT(b.rle.size(), (present + 40) * 8) << "absent pixels did not become runs";
    RectImage back = decodePart(unpackBrickImage(packBrickImage(b)), f, Rect{0, 0, 100, 100});
    for (int y = back.rect.y; y < back.rect.y + back.rect.h; ++y)
      for (int x = back.rect.x; x < back.rect.x + back.rect.w; ++x)
        for (int c = 0; c < 4; ++c) {
          const float want = img.at(x, y)[c], got = back.at(x, y)[c];
          if (f == WireFormat::Additive)
            EXPECT_NEAR(got, want, want / 2048.0f + 1e-7f);
          else
            EXPECT_EQ(got, want) << int(f) << " " << x << "," << y;  // exact, bit for bit
        }
    // Every present pixel's bytes 6 and 7 are not both zero (never a run marker).
    uint8_t wire[8];
    for (size_t i = 0; i < img.px.size(); i += 4)
      if (projectedPresent(f, &img.px[i])) {
        toProjected(f, &img.px[i], wire);
        EXPECT_NE(wire[6] | wire[7], 0);
      }
  }
}

TEST(ProjectionPixels, OperatorsAreOrderFree) {
  std::mt19937 rng(11);
  for (WireFormat f : kFormats)
    for (int trial = 0; trial < 200; ++trial) {
      float p[6][4];
      for (auto& q : p) randomPixel(f, rng, q);
      // ((((p0 p1) p2) p3) p4) p5 against a shuffled, pairwise tree grouping.
      float left[4] = {0, 0, 0, 0};
      for (auto& q : p) combineProjected(f, q, left);
      int idx[6] = {0, 1, 2, 3, 4, 5};
      std::shuffle(idx, idx + 6, rng);
      float a[4] = {0, 0, 0, 0}, b[4] = {0, 0, 0, 0}, c[4] = {0, 0, 0, 0};
      combineProjected(f, p[idx[0]], a), combineProjected(f, p[idx[1]], a);
      combineProjected(f, p[idx[2]], b), combineProjected(f, p[idx[3]], b), combineProjected(f, p[idx[4]], b);
      combineProjected(f, p[idx[5]], c);
      combineProjected(f, c, b);
      combineProjected(f, b, a);
      for (int k = 0; k < 4; ++k) {
        if (f == WireFormat::ValueMax || f == WireFormat::ValueMin)
          EXPECT_EQ(a[k], left[k]);  // max and min are exact in any order
        else
          EXPECT_NEAR(a[k], left[k], 1e-5f * (std::abs(left[k]) + 1.0f));
      }
    }
}

// Every rank count 1-4 and k = 2, 4: radix-k's frame equals combining every brick at once and
// colouring it, within one 8-bit step.
TEST(ProjectionPixels, RadixKMatchesOneCombine) {
  const int width = 37, height = 29;
  auto colour = [](float* px, size_t n) {  // a stand-in colouring: grey ramp of the value
    for (size_t i = 0; i < n; ++i) {
      float* p = px + 4 * i;
      if (!(p[3] > 0.0f)) continue;
      const float v = std::clamp(p[0] / p[3] * 0.1f + 0.4f, 0.0f, 1.0f);
      p[0] = p[1] = p[2] = v * 0.8f;
      p[3] = 0.8f;
    }
  };
  auto colourAdd = [](float* px, size_t n) {
    for (size_t i = 0; i < 4 * n; ++i) px[i] = std::min(px[i], 1.0f);
  };
  std::mt19937 rng(3);
  for (WireFormat f : kFormats)
    for (int ranks = 1; ranks <= 4; ++ranks)
      for (int k : {2, 4}) {
        const int bricks = 6;
        std::vector<std::vector<float>> floats(bricks);
        std::vector<BrickImage> images(bricks);
        for (int i = 0; i < bricks; ++i) {
          const int x0 = int(rng() % 20), y0 = int(rng() % 15);
          images[size_t(i)].brick_id = i;
          images[size_t(i)].rect = {x0, y0, 1 + int(rng() % unsigned(width - x0)),
                                    1 + int(rng() % unsigned(height - y0))};
          floats[size_t(i)].resize(size_t(images[size_t(i)].rect.area()) * 4);
          for (size_t p = 0; p < floats[size_t(i)].size(); p += 4) randomPixel(f, rng, &floats[size_t(i)][p]);
          encodeProjected(f, floats[size_t(i)], images[size_t(i)].rle, kMaxRun);
        }
        ImageF want(width, height);
        std::vector<const BrickImage*> all;
        for (const BrickImage& b : images) all.push_back(&b);
        std::reverse(all.begin(), all.end());  // any order: the operator does not care
        blendBackToFront(all, want, f);
        if (f == WireFormat::Additive) colourAdd(want.px.data(), size_t(width) * height);
        else colour(want.px.data(), size_t(width) * height);
        const ImageRGBA8 want8 = toRGBA8(want);

        VisibilityOrder order;
        order.bricks.resize(bricks);
        std::iota(order.bricks.begin(), order.bricks.end(), 0);
        order.ranks.resize(size_t(ranks));
        std::iota(order.ranks.begin(), order.ranks.end(), 0);
        std::vector<std::vector<BrickImage>> mine(static_cast<size_t>(ranks));
        for (int i = 0; i < bricks; ++i) mine[size_t(i % ranks)].push_back(images[size_t(i)]);
        CompositeOptions options;
        options.projection = f;
        if (f == WireFormat::Additive) options.colour_projection = colourAdd;
        else options.colour_projection = colour;
        Mailbox box;
        box.sent.resize(size_t(ranks));
        std::vector<CompositeStats> stats(static_cast<size_t>(ranks));
        std::vector<ImageRGBA8> frames(static_cast<size_t>(ranks));
        std::vector<std::string> errors(static_cast<size_t>(ranks));
        std::vector<std::thread> threads;
        for (int r = 0; r < ranks; ++r)
          threads.emplace_back([&, r] {
            try {
              ThreadTransport t(box, r, ranks);
              frames[size_t(r)] = radixKComposite(mine[size_t(r)], order, width, height, k, t,
                                                  stats[size_t(r)], options);
            } catch (const std::exception& e) {
              errors[size_t(r)] = e.what();
            }
          });
        for (auto& t : threads) t.join();
        for (int r = 0; r < ranks; ++r) ASSERT_EQ(errors[size_t(r)], "") << "rank " << r;
        int worst = 0;
        for (size_t i = 0; i < want8.px.size(); ++i)
          worst = std::max(worst, std::abs(int(want8.px[i]) - int(frames[0].px[i])));
        EXPECT_LE(worst, 1) << "format " << int(f) << " ranks " << ranks << " k " << k;
      }
}

constexpr WireFormat kBounded[] = {WireFormat::ValueMaxBounded, WireFormat::ValueMinBounded};

// A random bounded pixel (v, packed layer rgb, 0, flags): absent, a value, a layer, or both.
// Six pixels p (back to front) combined one by one into `left`, and the same order grouped as a
// tree, (p0 p1) (p2 p3 p4) (p5), each group back to front, then the groups back to front: an
// associative operator gives the same result bit for bit.
void expectGroupingFree(WireFormat f, const float (&p)[6][4], float* left) {
  for (auto& q : p) combineProjected(f, q, left);
  float a[4] = {0, 0, 0, 0}, b[4] = {0, 0, 0, 0}, c[4] = {0, 0, 0, 0};
  combineProjected(f, p[0], a), combineProjected(f, p[1], a);
  combineProjected(f, p[2], b), combineProjected(f, p[3], b), combineProjected(f, p[4], b);
  combineProjected(f, p[5], c);
  float all[4] = {0, 0, 0, 0};
  combineProjected(f, a, all), combineProjected(f, b, all), combineProjected(f, c, all);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(all[k], left[k]);
}

// The index of the frontmost of the six pixels that carries an opaque layer, -1 if none does.
int frontmostLayer(WireFormat f, const float (&p)[6][4]) {
  for (int i = 5; i >= 0; --i)
    if (boundedHasLayer(f, p[i])) return i;
  return -1;
}

void randomBoundedPixel(std::mt19937& rng, float* p) {
  std::uniform_real_distribution<float> u(-3.0f, 5.0f);
  for (int c = 0; c < 4; ++c) p[c] = 0.0f;
  const unsigned kind = rng() % 4;  // 0 absent, 1 value, 2 layer, 3 both
  if (kind & 1u) p[0] = u(rng), p[3] += 1.0f;
  if (kind & 2u) p[1] = float(rng() % 16777216u), p[3] += 2.0f;
}

TEST(ProjectionPixels, BoundedWireRoundTripIsExact) {
  std::mt19937 rng(5);
  for (WireFormat f : kBounded) {
    RectImage img(Rect{1, 2, 33, 7});
    for (size_t i = 0; i < img.px.size(); i += 4) randomBoundedPixel(rng, &img.px[i]);
    for (int x = 1; x < 34; ++x) std::fill_n(img.at(x, 4), 4, 0.0f);  // an absent row: a run
    BrickImage b = encodePart(img, img.rect, 1, f);
    RectImage back = decodePart(unpackBrickImage(packBrickImage(b)), f, Rect{0, 0, 64, 64});
    int layers = 0;
    for (int y = back.rect.y; y < back.rect.y + back.rect.h; ++y)
      for (int x = back.rect.x; x < back.rect.x + back.rect.w; ++x) {
        layers += boundedHasLayer(f, img.at(x, y));
        for (int c = 0; c < 4; ++c) EXPECT_EQ(back.at(x, y)[c], img.at(x, y)[c]) << x << "," << y << " " << c;
      }
    EXPECT_GT(layers, 20);
    uint8_t wire[8];
    for (size_t i = 0; i < img.px.size(); i += 4)
      if (projectedPresent(f, &img.px[i])) {
        toProjected(f, &img.px[i], wire);
        EXPECT_NE(wire[6] | wire[7], 0);
      }
  }
}

TEST(ProjectionPixels, BoundedOperatorKeepsTheVisibilityOrder) {
  std::mt19937 rng(13);
  int reversed_differs = 0;
  for (WireFormat f : kBounded)
    for (int trial = 0; trial < 300; ++trial) {
      float p[6][4];  // back to front
      for (auto& q : p) randomBoundedPixel(rng, q);
      float left[4] = {0, 0, 0, 0};
      expectGroupingFree(f, p, left);
      // The frontmost layer hides what lies behind it: the result's value comes from in front of it.
      const int front_layer = frontmostLayer(f, p);
      if (front_layer >= 0) {
        EXPECT_EQ(left[1], p[front_layer][1]);
        float v[4] = {0, 0, 0, 0};
        for (int i = front_layer; i < 6; ++i) {
          float q[4] = {p[i][0], 0.0f, 0.0f, boundedHasValue(f, p[i]) ? 1.0f : 0.0f};
          combineProjected(f == WireFormat::ValueMaxBounded ? WireFormat::ValueMax : WireFormat::ValueMin, q, v);
        }
        EXPECT_EQ(boundedHasValue(f, left), v[3] > 0.0f);
        if (v[3] > 0.0f) EXPECT_EQ(left[0], v[0]);
      }
      float rev[4] = {0, 0, 0, 0};
      for (int i = 5; i >= 0; --i) combineProjected(f, p[i], rev);
      reversed_differs += !std::equal(rev, rev + 4, left);
    }
  EXPECT_GT(reversed_differs, 100);  // not commutative: the order is what bounds the rays
}

// Radix-k on 1-4 ranks, k = 2 and 4, each rank holding a run of the visibility order (as the
// kd-split's assignment does): the frame equals one ordered combine of every brick, exactly.
TEST(ProjectionPixels, BoundedRadixKMatchesOneOrderedCombine) {
  const int width = 31, height = 23;
  auto colour = [](float* px, size_t n) {  // a stand-in colouring of value, layer and flags
    for (size_t i = 0; i < n; ++i) {
      float* p = px + 4 * i;
      if (!(p[3] > 0.0f)) continue;
      const float v = boundedHasValue(WireFormat::ValueMaxBounded, p) ? std::clamp(p[0] * 0.1f + 0.4f, 0.0f, 1.0f) : 0.0f;
      const float s = float(uint32_t(p[1]) & 0xffu) / 255.0f;
      p[0] = v, p[1] = s, p[2] = p[3] / 3.0f, p[3] = 1.0f;
    }
  };
  std::mt19937 rng(17);
  for (WireFormat f : kBounded)
    for (int ranks = 1; ranks <= 4; ++ranks)
      for (int k : {2, 4}) {
        const int bricks = 8;
        std::vector<BrickImage> images(bricks);
        for (int i = 0; i < bricks; ++i) {
          const int x0 = int(rng() % 16), y0 = int(rng() % 12);
          images[size_t(i)].brick_id = i;
          images[size_t(i)].rect = {x0, y0, 1 + int(rng() % unsigned(width - x0)), 1 + int(rng() % unsigned(height - y0))};
          std::vector<float> px(size_t(images[size_t(i)].rect.area()) * 4);
          for (size_t p = 0; p < px.size(); p += 4) randomBoundedPixel(rng, &px[p]);
          encodeProjected(f, px, images[size_t(i)].rle, kMaxRun);
        }
        ImageF want(width, height);
        std::vector<const BrickImage*> all;
        for (const BrickImage& b : images) all.push_back(&b);  // brick 0 at the back
        blendBackToFront(all, want, f);
        colour(want.px.data(), size_t(width) * height);
        const ImageRGBA8 want8 = toRGBA8(want);

        VisibilityOrder order;
        order.bricks.resize(bricks);
        std::iota(order.bricks.begin(), order.bricks.end(), 0);
        order.ranks.resize(size_t(ranks));
        std::iota(order.ranks.begin(), order.ranks.end(), 0);
        std::vector<std::vector<BrickImage>> mine(static_cast<size_t>(ranks));
        for (int i = 0; i < bricks; ++i) mine[size_t(i * ranks / bricks)].push_back(images[size_t(i)]);
        CompositeOptions options;
        options.projection = f;
        options.colour_projection = colour;
        Mailbox box;
        box.sent.resize(size_t(ranks));
        std::vector<CompositeStats> stats(static_cast<size_t>(ranks));
        std::vector<ImageRGBA8> frames(static_cast<size_t>(ranks));
        std::vector<std::string> errors(static_cast<size_t>(ranks));
        std::vector<std::thread> threads;
        for (int r = 0; r < ranks; ++r)
          threads.emplace_back([&, r] {
            try {
              ThreadTransport t(box, r, ranks);
              frames[size_t(r)] = radixKComposite(mine[size_t(r)], order, width, height, k, t, stats[size_t(r)], options);
            } catch (const std::exception& e) {
              errors[size_t(r)] = e.what();
            }
          });
        for (auto& t : threads) t.join();
        for (int r = 0; r < ranks; ++r) ASSERT_EQ(errors[size_t(r)], "") << "rank " << r;
        EXPECT_EQ(frames[0].px, want8.px) << "format " << int(f) << " ranks " << ranks << " k " << k;
      }
}

}  // namespace

// The bounded sums (average, additive): 12 bytes a pixel. Values are multiples of 1/8 below 4, so
// every sum of a few of them is exact in float and in half, and the groupings compare exactly.
constexpr WireFormat kBoundedSums[] = {WireFormat::ValueSumBounded, WireFormat::AdditiveBounded};

void randomBoundedSumPixel(WireFormat f, std::mt19937& rng, float* p) {
  const unsigned kind = rng() % 4;  // 0 absent, 1 sums, 2 layer, 3 both
  const uint32_t layer = (kind & 2u) ? 1u + rng() % 16777215u : 0u;
  auto eighth = [&] { return float(rng() % 32u) / 8.0f; };
  if (f == WireFormat::ValueSumBounded) {
    p[0] = (kind & 1u) ? eighth() - 2.0f : 0.0f;
    p[1] = float(layer);
    p[2] = (kind & 1u) ? float(1 + rng() % 5u) : 0.0f;
    p[3] = float(kind);
    return;
  }
  float sum[4] = {0, 0, 0, 0};
  if (kind & 1u)
    for (float& x : sum) x = eighth();
  packAdditiveBounded(sum, layer, int(kind), p);
}

// The sums of a bounded-sum pixel, the layer and the flags, for comparisons.
struct SumsOf {
  float a = 0, b = 0, c = 0, d = 0;
  uint32_t layer = 0;
  int flags = 0;
};
SumsOf sumsOf(WireFormat f, const float* p) {
  SumsOf s;
  s.flags = boundedFlags(f, p);
  s.layer = (s.flags & 2) ? boundedLayer(f, p) : 0u;
  if (f == WireFormat::ValueSumBounded) {
    s.a = p[0], s.b = p[2];
  } else {
    float x[4];
    additiveBoundedSums(p, x);
    s.a = x[0], s.b = x[1], s.c = x[2], s.d = x[3];
  }
  return s;
}

TEST(ProjectionPixels, BoundedSumsWireRoundTripIsExact) {
  std::mt19937 rng(23);
  for (WireFormat f : kBoundedSums) {
    EXPECT_EQ(pixelBytes(f), 12);
    RectImage img(Rect{3, 1, 29, 9});
    for (size_t i = 0; i < img.px.size(); i += 4) randomBoundedSumPixel(f, rng, &img.px[i]);
    for (int x = 3; x < 32; ++x) std::fill_n(img.at(x, 5), 4, 0.0f);  // an absent row: a run
    BrickImage b = encodePart(img, img.rect, 1, f);
    RectImage back = decodePart(unpackBrickImage(packBrickImage(b)), f, Rect{0, 0, 64, 64});
    int layers = 0, sums = 0;
    for (int y = back.rect.y; y < back.rect.y + back.rect.h; ++y)
      for (int x = back.rect.x; x < back.rect.x + back.rect.w; ++x) {
        layers += boundedHasLayer(f, img.at(x, y));
        sums += boundedHasValue(f, img.at(x, y));
        for (int c = 0; c < 4; ++c) EXPECT_EQ(back.at(x, y)[c], img.at(x, y)[c]) << x << "," << y << " " << c;
      }
    EXPECT_GT(layers, 40);
    EXPECT_GT(sums, 40);
    uint8_t wire[12];
    for (size_t i = 0; i < img.px.size(); i += 4)
      if (projectedPresent(f, &img.px[i])) {
        toProjected(f, &img.px[i], wire);
        EXPECT_FALSE(rleIsRun(wire, 12));
      }
  }
}

TEST(ProjectionPixels, BoundedSumsOperatorKeepsTheVisibilityOrder) {
  std::mt19937 rng(29);
  for (WireFormat f : kBoundedSums) {
    int reversed_differs = 0, bounded_seen = 0;
    for (int trial = 0; trial < 400; ++trial) {
      float p[6][4];  // back to front
      for (auto& q : p) randomBoundedSumPixel(f, rng, q);
      float left[4] = {0, 0, 0, 0};
      expectGroupingFree(f, p, left);
      // Only what lies in front of the frontmost layer adds up, and that layer is the pixel's.
      const int front_layer = frontmostLayer(f, p);
      SumsOf want;
      want.layer = front_layer >= 0 ? boundedLayer(f, p[front_layer]) : 0u;
      want.flags = front_layer >= 0 ? 2 : 0;
      for (int i = std::max(front_layer, 0); i < 6; ++i) {
        const SumsOf q = sumsOf(f, p[i]);
        if (!(q.flags & 1)) continue;
        want.a += q.a, want.b += q.b, want.c += q.c, want.d += q.d, want.flags |= 1;
      }
      const SumsOf got = sumsOf(f, left);
      EXPECT_EQ(got.flags, want.flags);
      EXPECT_EQ(got.layer, want.layer);
      EXPECT_EQ(got.a, want.a);
      EXPECT_EQ(got.b, want.b);
      EXPECT_EQ(got.c, want.c);
      EXPECT_EQ(got.d, want.d);
      bounded_seen += front_layer > 0;
      float rev[4] = {0, 0, 0, 0};
      for (int i = 5; i >= 0; --i) combineProjected(f, p[i], rev);
      reversed_differs += !std::equal(rev, rev + 4, left);
    }
    EXPECT_GT(bounded_seen, 100);
    EXPECT_GT(reversed_differs, 100);  // not commutative: the order is what bounds the rays
  }
}

}  // namespace sortlast
