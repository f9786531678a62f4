// The radix-k schedule (compositing/schedule.h), checked without images: its shape for every
// participant count and k, region splitting, and a symbolic run in which every pixel records the
// positions composited into it, which must come out as 0, 1, ..., n - 1 (far to near) exactly
// once in every pixel of the frame.
#include "compositing/schedule.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

namespace sortlast {
namespace {

bool inside(const Rect& inner, const Rect& outer) {
  return inner.x >= outer.x && inner.y >= outer.y && inner.x + inner.w <= outer.x + outer.w &&
         inner.y + inner.h <= outer.y + outer.h;
}

TEST(SplitRect, PartitionsAlongTheLongerSide) {
  for (Rect r : {Rect{3, 5, 257, 131}, Rect{0, 0, 7, 19}, Rect{2, 2, 5, 5}, Rect{0, 0, 3, 1},
                 Rect{10, 4, 1, 1}})
    for (int k = 1; k <= 8; ++k) {
      SCOPED_TRACE(std::to_string(r.w) + "x" + std::to_string(r.h) + " k " + std::to_string(k));
      auto parts = splitRect(r, k);
      ASSERT_EQ(parts.size(), size_t(k));
      const bool along_x = r.w >= r.h;
      const int len = along_x ? r.w : r.h;
      long long area = 0;
      int next = along_x ? r.x : r.y, smallest = len, largest = 0;
      for (const Rect& p : parts) {
        int lo = along_x ? p.x : p.y, size = along_x ? p.w : p.h;
        EXPECT_EQ(lo, next);  // in order, no gap, no overlap
        next = lo + size;
        EXPECT_EQ(along_x ? p.h : p.w, along_x ? r.h : r.w);  // the other side is whole
        EXPECT_EQ(along_x ? p.y : p.x, along_x ? r.y : r.x);
        smallest = std::min(smallest, size);
        largest = std::max(largest, size);
        area += p.area();
      }
      EXPECT_EQ(next, (along_x ? r.x : r.y) + len);
      EXPECT_LE(largest - smallest, 1);
      EXPECT_EQ(area, r.area());
    }
  for (const Rect& p : splitRect(Rect{4, 4, 0, 9}, 3)) EXPECT_TRUE(p.empty());
}

TEST(RadixKSchedule, Shape) {
  for (int k = 2; k <= 9; ++k)
    for (int n = 0; n <= 64; ++n) {
      SCOPED_TRACE("n " + std::to_string(n) + " k " + std::to_string(k));
      RadixKSchedule s = makeRadixKSchedule(n, k);
      ASSERT_EQ(s.participants, n);
      int product = 1;
      for (size_t t = 0; t < s.radices.size(); ++t) {
        EXPECT_GE(s.radices[t], 2);
        EXPECT_LE(s.radices[t], k);
        if (t > 0) {
          EXPECT_LE(s.radices[t], s.radices[t - 1]);
        }  // largest first
        product *= s.radices[t];
      }
      EXPECT_EQ(product, std::max(1, s.units()));
      EXPECT_GE(s.folds, 0);
      EXPECT_LE(s.folds, s.units());  // a unit absorbs at most one fold
      // No count between units() and n can be split into rounds of at most k.
      for (int m = s.units() + 1; m <= n; ++m) {
        int r = m;
        for (int f = k; f >= 2; --f)
          while (r % f == 0) r /= f;
        EXPECT_NE(r, 1) << "count " << m << " would have needed fewer folds";
      }
      if (k == 2 && n > 0) {  // binary-swap: the largest power of two
        int p = 1;
        while (2 * p <= n) p *= 2;
        EXPECT_EQ(s.units(), p);
      }
      // Units cover positions 0 .. n-1 in order, each exactly once.
      int next = 0;
      for (int u = 0; u < s.units(); ++u) {
        EXPECT_EQ(s.firstPosition(u), next);
        EXPECT_LE(s.lastPosition(u) - s.firstPosition(u), 1);
        next = s.lastPosition(u) + 1;
      }
      EXPECT_EQ(next, n);
    }
}

TEST(RadixKSchedule, HandCases) {
  auto radices = [](int n, int k) { return makeRadixKSchedule(n, k).radices; };
  using V = std::vector<int>;
  EXPECT_EQ(radices(1, 2), V{});
  EXPECT_EQ(radices(8, 2), (V{2, 2, 2}));
  EXPECT_EQ(radices(8, 4), (V{4, 2}));
  EXPECT_EQ(radices(6, 4), (V{3, 2}));
  EXPECT_EQ(radices(6, 2), (V{2, 2}));
  EXPECT_EQ(makeRadixKSchedule(6, 2).folds, 2);
  EXPECT_EQ(makeRadixKSchedule(7, 4).folds, 1);  // 6 = 3 x 2
  EXPECT_EQ(radices(7, 8), V{7});                // k >= n: one round, IceT's direct send
  EXPECT_EQ(makeRadixKSchedule(5, 3).folds, 1);
  EXPECT_EQ(radices(5, 3), (V{2, 2}));
  RadixKSchedule s = makeRadixKSchedule(8, 2);
  EXPECT_EQ(s.group(0, 5), (V{4, 5}));
  EXPECT_EQ(s.group(1, 5), (V{5, 7}));
  EXPECT_EQ(s.group(2, 5), (V{1, 5}));
  EXPECT_EQ(s.mergedUnits(2, 5), (std::pair<int, int>{4, 7}));
  EXPECT_THROW(makeRadixKSchedule(4, 1), std::invalid_argument);
}

// Runs the schedule on symbolic images: every pixel holds the list of positions blended into it,
// far to near; "over" appends. The frame must end up with the whole list in every pixel, held by
// exactly one unit, and nothing may be held outside a unit's region.
void runSymbolic(int n, int k, const Rect& whole) {
  using Layers = std::vector<int>;
  using Image = std::map<std::pair<int, int>, Layers>;  // pixel -> positions, far to near
  RadixKSchedule s = makeRadixKSchedule(n, k);
  auto full = [&](int position) {
    Image img;
    for (int y = whole.y; y < whole.y + whole.h; ++y)
      for (int x = whole.x; x < whole.x + whole.w; ++x) img[{x, y}] = {position};
    return img;
  };
  auto in = [](const Rect& r, const std::pair<int, int>& p) {
    return p.first >= r.x && p.first < r.x + r.w && p.second >= r.y && p.second < r.y + r.h;
  };
  std::vector<Image> unit(size_t(s.units()));
  for (int u = 0; u < s.units(); ++u) {
    unit[size_t(u)] = full(s.firstPosition(u));
    if (s.lastPosition(u) != s.firstPosition(u))  // the nearer one folds in: it goes in front
      for (auto& [px, layers] : unit[size_t(u)]) layers.push_back(s.lastPosition(u));
  }
  for (int t = 0; t < s.rounds(); ++t) {
    std::vector<Image> next(unit.size());
    for (int u = 0; u < s.units(); ++u) {
      auto group = s.group(t, u);
      ASSERT_EQ(int(group.size()), s.radices[size_t(t)]);
      ASSERT_EQ(group[size_t(s.digit(t, u))], u);
      Rect region = s.region(t, u, whole);
      auto parts = splitRect(region, int(group.size()));
      for (size_t m = 0; m + 1 < group.size(); ++m) {
        ASSERT_EQ(s.region(t, group[m], whole), region) << "group members must share the region";
        // Members hold neighbouring runs of units, in order.
        ASSERT_EQ(s.mergedUnits(t, group[m]).second + 1, s.mergedUnits(t, group[m + 1]).first);
      }
      ASSERT_EQ(s.region(t + 1, u, whole), parts[size_t(s.digit(t, u))]);
      for (int member : group)
        for (const auto& [px, layers] : unit[size_t(member)]) {
          ASSERT_TRUE(in(region, px)) << "unit " << member << " holds a pixel outside its region";
          if (!in(parts[size_t(s.digit(t, u))], px)) continue;
          Layers& out = next[size_t(u)][px];
          out.insert(out.end(), layers.begin(), layers.end());
        }
    }
    unit = std::move(next);
  }
  Layers all;
  for (int p = 0; p < n; ++p) all.push_back(p);
  std::map<std::pair<int, int>, int> holders;
  for (int u = 0; u < s.units(); ++u) {
    Rect final_region = s.region(s.rounds(), u, whole);
    for (const auto& [px, layers] : unit[size_t(u)]) {
      ASSERT_TRUE(in(final_region, px));
      ASSERT_EQ(layers, all) << "pixel " << px.first << "," << px.second << " of unit " << u;
      ++holders[px];
    }
  }
  if (n == 0) return;
  ASSERT_EQ(holders.size(), size_t(whole.area()));
  for (const auto& [px, count] : holders) ASSERT_EQ(count, 1);
}

TEST(RadixKSchedule, SymbolicRunComposesEveryPixelInOrder) {
  for (int k = 2; k <= 4; ++k)
    for (int n = 1; n <= 8; ++n)
      for (Rect whole : {Rect{2, 3, 13, 7}, Rect{0, 0, 3, 2}, Rect{5, 5, 1, 1}}) {
        SCOPED_TRACE("n " + std::to_string(n) + " k " + std::to_string(k) + " whole " +
                     std::to_string(whole.w) + "x" + std::to_string(whole.h));
        runSymbolic(n, k, whole);
      }
  runSymbolic(12, 3, Rect{0, 0, 11, 9});
  runSymbolic(27, 9, Rect{0, 0, 10, 10});
}

}  // namespace
}  // namespace sortlast
