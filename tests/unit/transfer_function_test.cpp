// Transfer functions (transfer/transfer_function.h): interpolation, extinction, maxOpacity,
// the baked lookup table.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.h"
#include "transfer/transfer_function.h"

namespace sortlast {
namespace {

// Three points over the data range [10, 20], unit length 0.5.
TransferFunction threePoints() {
  return TransferFunction({{0.0, 0.0, 0.2, 1.0, 0.0}, {0.5, 1.0, 0.6, 0.0, 0.4}, {1.0, 0.5, 1.0, 0.5, 0.8}},
                          10.0, 20.0, 0.5);
}

TEST(TransferFunction, PiecewiseLinearColourAndOpacity) {
  TransferFunction tf = threePoints();
  // At the control points.
  EXPECT_NEAR(tf.opacity(10.0), 0.0, 1e-12);
  EXPECT_NEAR(tf.opacity(15.0), 0.4, 1e-12);
  EXPECT_NEAR(tf.opacity(20.0), 0.8, 1e-12);
  // Between them: data 12.5 is normalised 0.25, halfway between points 0 and 1.
  auto c = tf.colour(12.5);
  EXPECT_NEAR(c[0], 0.5, 1e-12);
  EXPECT_NEAR(c[1], 0.4, 1e-12);
  EXPECT_NEAR(c[2], 0.5, 1e-12);
  EXPECT_NEAR(tf.opacity(12.5), 0.2, 1e-12);
  // Data 19 is normalised 0.9: 80% of the way from point 1 to point 2.
  c = tf.colour(19.0);
  EXPECT_NEAR(c[0], 1.0 + 0.8 * (0.5 - 1.0), 1e-12);
  EXPECT_NEAR(c[1], 0.6 + 0.8 * (1.0 - 0.6), 1e-12);
  EXPECT_NEAR(c[2], 0.0 + 0.8 * 0.5, 1e-12);
  EXPECT_NEAR(tf.opacity(19.0), 0.4 + 0.8 * 0.4, 1e-12);
  // Outside the range: clamped to the ends.
  EXPECT_NEAR(tf.opacity(-100.0), 0.0, 1e-12);
  EXPECT_NEAR(tf.colour(-100.0)[2], 1.0, 1e-12);
  EXPECT_NEAR(tf.opacity(1e9), 0.8, 1e-12);
  EXPECT_NEAR(tf.colour(1e9)[0], 0.5, 1e-12);
  EXPECT_NEAR(tf.normalise(12.5), 0.25, 1e-12);
  EXPECT_EQ(tf.normalise(5.0), 0.0);
  EXPECT_EQ(tf.normalise(25.0), 1.0);
}

TEST(TransferFunction, ControlPointsNotAtTheEnds) {
  // Points at 0.2 and 0.6 only: constant before the first and after the last.
  TransferFunction tf({{0.2, 0.1, 0.1, 0.1, 0.3}, {0.6, 0.9, 0.9, 0.9, 0.7}}, 0.0, 1.0, 1.0);
  EXPECT_NEAR(tf.opacity(0.0), 0.3, 1e-12);
  EXPECT_NEAR(tf.opacity(0.1), 0.3, 1e-12);
  EXPECT_NEAR(tf.opacity(0.4), 0.5, 1e-12);
  EXPECT_NEAR(tf.opacity(0.9), 0.7, 1e-12);
  EXPECT_NEAR(tf.colour(0.5)[1], 0.1 + 0.75 * 0.8, 1e-12);
}

TEST(TransferFunction, ExtinctionIsMinusLogOfTransmittancePerUnitLength) {
  TransferFunction tf = threePoints();
  for (double v : {10.0, 11.0, 12.5, 15.0, 17.3, 20.0}) {
    double a = tf.opacity(v);
    EXPECT_NEAR(tf.extinction(v), -std::log(1.0 - a) / 0.5, 1e-12) << "value " << v;
  }
  EXPECT_NEAR(tf.extinction(20.0), -std::log(0.2) / 0.5, 1e-12);
  EXPECT_EQ(tf.extinction(10.0), 0.0);
  // Opacity 1 is capped: extinction stays finite.
  TransferFunction opaque({{0.0, 1, 1, 1, 1.0}}, 0.0, 1.0, 2.0);
  double tau = opaque.extinction(0.5);
  EXPECT_TRUE(std::isfinite(tau));
  EXPECT_NEAR(tau, -std::log(1.0 - TransferFunction::kMaxOpacity) / 2.0, 1e-9);
}

TEST(TransferFunction, MaxOpacityFindsInteriorPeak) {
  // A spike at 0.5 with zero opacity at both ends of the interval.
  TransferFunction tf({{0.0, 0, 0, 0, 0.0}, {0.4, 0, 0, 0, 0.0}, {0.5, 1, 1, 1, 0.6},
                       {0.6, 0, 0, 0, 0.0}, {1.0, 0, 0, 0, 0.0}},
                      0.0, 100.0, 1.0);
  EXPECT_EQ(tf.opacity(35.0), 0.0);
  EXPECT_EQ(tf.opacity(65.0), 0.0);
  EXPECT_NEAR(tf.maxOpacity(35.0, 65.0), 0.6, 1e-12);
  EXPECT_NEAR(tf.maxOpacity(0.0, 100.0), 0.6, 1e-12);
  // Intervals that miss the spike are invisible.
  EXPECT_EQ(tf.maxOpacity(0.0, 40.0), 0.0);
  EXPECT_EQ(tf.maxOpacity(60.0, 100.0), 0.0);
  // Partly up the ramp: the endpoint value is the maximum.
  EXPECT_NEAR(tf.maxOpacity(30.0, 45.0), 0.3, 1e-12);
  EXPECT_NEAR(tf.maxOpacity(52.0, 70.0), 0.48, 1e-12);
}

TEST(TransferFunction, BakeTableEndsAreTheEndPoints) {
  TransferFunction tf = threePoints();
  for (int n : {2, 3, 256, 4096}) {
    auto t = tf.bakeTable(n);
    ASSERT_EQ(t.size(), 4u * n);
    // First entry: point 0 (r, g, b, tau of a = 0).
    EXPECT_FLOAT_EQ(t[0], 0.0f);
    EXPECT_FLOAT_EQ(t[1], 0.2f);
    EXPECT_FLOAT_EQ(t[2], 1.0f);
    EXPECT_FLOAT_EQ(t[3], 0.0f);
    // Last entry: point 2, tau = -ln(1 - 0.8) / 0.5.
    const float* last = &t[4 * (n - 1)];
    EXPECT_FLOAT_EQ(last[0], 0.5f);
    EXPECT_FLOAT_EQ(last[1], 1.0f);
    EXPECT_FLOAT_EQ(last[2], 0.5f);
    EXPECT_FLOAT_EQ(last[3], float(-std::log(0.2) / 0.5));
  }
  // Entry i is the value at normalised i / (n - 1): with n = 3 the middle entry is point 1.
  auto t = tf.bakeTable(3);
  EXPECT_FLOAT_EQ(t[4], 1.0f);
  EXPECT_FLOAT_EQ(t[5], 0.6f);
  EXPECT_FLOAT_EQ(t[6], 0.0f);
  EXPECT_FLOAT_EQ(t[7], float(-std::log(0.6) / 0.5));
}

// Empty-block rule (tableSpanVisible): a span of values reads table entries floor(x(vmin)) ..
// ceil(x(vmax)) and no others. Each case fails if the rule pads by an entry, or rounds either end
// the other way.
TEST(TransferFunction, TableSpanReadsExactlyItsEntries) {
  // 11 entries over [0, 100] (one every 10); opacity only between 40 and 60, peak 1 at 50.
  TransferFunction tf({{0.0, 0, 0, 0, 0.0}, {0.4, 0, 0, 0, 0.0}, {0.5, 1, 1, 1, 1.0},
                       {0.6, 0, 0, 0, 0.0}, {1.0, 0, 0, 0, 0.0}},
                      0.0, 100.0, 1.0);
  const int n = 11;
  EXPECT_FALSE(tf.tableSpanVisible(n, 40.0, 40.0));  // on entry 4 (zero) only: a pad would see 5
  EXPECT_FALSE(tf.tableSpanVisible(n, 30.0, 40.0));  // entries 3, 4
  EXPECT_TRUE(tf.tableSpanVisible(n, 35.0, 41.0));   // 41 blends in entry 5: floor(vmax) misses it
  EXPECT_TRUE(tf.tableSpanVisible(n, 59.0, 70.0));   // 59 reads entry 5: ceil(vmin) misses it
  EXPECT_FALSE(tf.tableSpanVisible(n, 60.0, 100.0)); // entries 6 .. 10
  EXPECT_FALSE(tf.tableSpanVisible(n, -50.0, 40.0)); // clamped below the range: entries 0 .. 4
  EXPECT_FALSE(tf.tableSpanVisible(n, 60.0, 500.0)); // clamped above
  EXPECT_TRUE(tf.tableSpanVisible(n, 0.0, 100.0));
}

// Against brute force: a span is visible exactly when some value in it has non-zero filtered
// table opacity. Sampling the span's ends and every node and midpoint between nodes inside it
// meets every (entry, positive weight) pair the span can read.
TEST(TransferFunction, TableSpanAgreesWithFilteredLookups) {
  unsigned state = 12345u;
  auto uniform = [&]() { state = state * 1664525u + 1013904223u; return (state >> 8) / 16777216.0; };
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<TfPoint> points{{0.0, 0, 0, 0, uniform() < 0.5 ? 0.0 : uniform()}};
    for (double x = 0.1 + 0.2 * uniform(); x < 1.0; x += 0.05 + 0.3 * uniform())
      points.push_back({x, 0, 0, 0, uniform() < 0.6 ? 0.0 : uniform()});
    points.push_back({1.0, 0, 0, 0, uniform() < 0.5 ? 0.0 : uniform()});
    TransferFunction tf(points, -3.0, 5.0, 1.0);
    const int n = 4 + int(uniform() * 60);
    const std::vector<float> table = tf.bakeTable(n);
    auto filtered = [&](double v) {
      const double x = std::clamp((v + 3.0) / 8.0, 0.0, 1.0) * (n - 1);
      const int i = std::min(int(std::floor(x)), n - 1), j = std::min(i + 1, n - 1);
      const double f = x - i;
      return (1.0 - f) * table[4 * i + 3] + f * table[4 * j + 3];
    };
    for (int span = 0; span < 20; ++span) {
      double a = -4.0 + 10.0 * uniform(), b = -4.0 + 10.0 * uniform();
      if (uniform() < 0.3) a = -3.0 + 8.0 * std::round(uniform() * (n - 1)) / (n - 1);  // on a node
      if (a > b) std::swap(a, b);
      bool any = filtered(a) > 0.0 || filtered(b) > 0.0;
      for (int k = 0; k < n; ++k)
        for (double node : {double(k), k + 0.5}) {
          const double v = -3.0 + 8.0 * node / (n - 1);
          if (v > a && v < b) any = any || filtered(v) > 0.0;
        }
      EXPECT_EQ(tf.tableSpanVisible(n, a, b), any) << "trial " << trial << " span [" << a << ", " << b << "] n " << n;
    }
  }
}

// The raw values where the function's slope changes (the reference cuts its steps there): interior
// points where a channel bends, the range's ends where a channel slopes into the clamp, a jump
// (two points at one value); not a collinear point, nor an end where every channel is flat.
TEST(TransferFunction, KinkValuesAreWhereASlopeChanges) {
  // Over [10, 20]: 0 -> 0.25 -> 0.5 collinear in every channel; a bend at 0.75; flat from 0.75 to 1
  // in every channel, so the top of the range is no kink; the bottom is (the channels slope there).
  const TransferFunction tf({{0.0, 0.0, 0.0, 0.0, 0.0}, {0.25, 0.25, 0.25, 0.25, 0.25},
                             {0.5, 0.5, 0.5, 0.5, 0.5}, {0.75, 0.5, 0.5, 0.5, 0.9}, {1.0, 0.5, 0.5, 0.5, 0.9}},
                            10.0, 20.0, 1.0);
  const std::vector<double> want = {10.0, 15.0, 17.5};
  ASSERT_EQ(tf.kinkValues().size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) EXPECT_NEAR(tf.kinkValues()[i], want[i], 1e-12);
  // A jump at 0.4, inside points that are otherwise flat: one kink, there.
  const TransferFunction jump({{0.0, 0, 0, 0, 0}, {0.4, 0, 0, 0, 0}, {0.4, 1, 1, 1, 0.5}, {1.0, 1, 1, 1, 0.5}},
                              0.0, 1.0, 1.0);
  ASSERT_EQ(jump.kinkValues().size(), 1u);
  EXPECT_NEAR(jump.kinkValues()[0], 0.4, 1e-12);
  // Under a log scale the points are raw values through the scale's inverse.
  const TransferFunction lg({{0.0, 0, 0, 0, 0}, {0.5, 1, 1, 1, 0.5}, {1.0, 1, 1, 1, 0.5}}, 1.0, 100.0, 1.0,
                            ValueScale{ValueScaleKind::kLog});
  ASSERT_EQ(lg.kinkValues().size(), 2u);
  EXPECT_NEAR(lg.kinkValues()[0], 1.0, 1e-9);
  EXPECT_NEAR(lg.kinkValues()[1], 10.0, 1e-9);
  // A colour bend where opacity runs straight on (a colour map's point): a kink, not opacity's.
  const TransferFunction cm({{0.0, 0, 0, 0, 0}, {0.5, 1, 0, 0, 0.25}, {1.0, 1, 1, 0, 0.5}}, 0.0, 1.0, 1.0);
  ASSERT_EQ(cm.kinkValues().size(), 3u);  // 0, 0.5 (colour) and 1 (the clamp)
  ASSERT_EQ(cm.opacityKinkValues().size(), 2u);
  EXPECT_NEAR(cm.opacityKinkValues()[0], 0.0, 1e-12);
  EXPECT_NEAR(cm.opacityKinkValues()[1], 1.0, 1e-12);
  // symlog bends at +-linear_width inside the range, with every channel that is not flat there.
  const TransferFunction sl({{0.0, 0, 0, 0, 0}, {1.0, 1, 1, 1, 1}}, -100.0, 100.0, 1.0,
                            ValueScale{ValueScaleKind::kSymlog, 2.0});
  const std::vector<double> sl_want = {-100.0, -2.0, 2.0, 100.0};
  ASSERT_EQ(sl.kinkValues().size(), sl_want.size());
  ASSERT_EQ(sl.opacityKinkValues().size(), sl_want.size());
  for (size_t i = 0; i < sl_want.size(); ++i) EXPECT_NEAR(sl.kinkValues()[i], sl_want[i], 1e-9);
}

TEST(TransferFunction, InvalidPointsThrow) {
  EXPECT_THROW(TransferFunction({}, 0.0, 1.0, 1.0), InputError);
  EXPECT_THROW(TransferFunction({{0.5, 0, 0, 0, 1.5}}, 0.0, 1.0, 1.0), InputError);
  EXPECT_THROW(TransferFunction({{0.6, 0, 0, 0, 0}, {0.4, 0, 0, 0, 0}}, 0.0, 1.0, 1.0), InputError);
  EXPECT_THROW(TransferFunction({{0.0, 0, 0, 0, 0}}, 1.0, 1.0, 1.0), InputError);
  EXPECT_THROW(TransferFunction({{0.0, 0, 0, 0, 0}}, 0.0, 1.0, 0.0), InputError);
  EXPECT_THROW(TransferFunction::preset("rainbow"), InputError);
}

}  // namespace
}  // namespace sortlast
