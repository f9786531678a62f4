// Transfer functions (common/transfer_function.h): interpolation, extinction, maxOpacity,
// the baked lookup table.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/error.h"
#include "common/transfer_function.h"

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
