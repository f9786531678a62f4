// transfer.scale (transfer/value_scale.h) through the transfer function, its table, block
// classification (empty-space skipping and the adaptive step rule), pre-integration and the
// scene's checks: each against the closed form of log10 and matplotlib's SymLogNorm.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "input_error_of.h"
#include "render/volume/step_rule.h"
#include "scene/scene.h"
#include "transfer/preintegration.h"
#include "transfer/transfer_function.h"

namespace sortlast {
namespace {

// Opacity = normalised place (the "ramp"), colour (x, 0, 1 - x), over [1, 1000] in log10.
TransferFunction logRamp() {
  return TransferFunction({{0.0, 0.0, 0.0, 1.0, 0.0}, {1.0, 1.0, 0.0, 0.0, 1.0}}, 1.0, 1000.0, 1.0,
                          ValueScale{ValueScaleKind::kLog, 1.0});
}

TEST(ValueScale, SymlogIsMatplotlibsSymLogNorm) {
  const ValueScale s{ValueScaleKind::kSymlog, 2.0};
  const double c = 1.0 / (1.0 - 0.1);  // linscale / (1 - 1 / base)
  EXPECT_NEAR(s.apply(0.0), 0.0, 1e-15);
  EXPECT_NEAR(s.apply(1.0), c, 1e-12);  // linear inside +-w
  EXPECT_NEAR(s.apply(-2.0), -2.0 * c, 1e-12);
  EXPECT_NEAR(s.apply(200.0), 2.0 * (c + 2.0), 1e-12);  // w (c + log10(v / w))
  EXPECT_NEAR(s.apply(-20.0), -2.0 * (c + 1.0), 1e-12);
  for (double v : {-5e4, -3.0, -2.0, -0.5, 0.0, 1e-3, 2.0, 2.0001, 7.0, 1e6}) {
    EXPECT_NEAR(s.inverse(s.apply(v)), v, 1e-9 * std::max(1.0, std::abs(v))) << v;
    EXPECT_LT(s.apply(v), s.apply(v + 1e-3 * std::max(1.0, std::abs(v)))) << "increasing at " << v;
  }
}

TEST(ValueScale, LogPlacesValuesInDecades) {
  const TransferFunction tf = logRamp();
  EXPECT_NEAR(tf.normalise(10.0), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(tf.normalise(100.0), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(tf.opacity(std::sqrt(10.0)), 1.0 / 6.0, 1e-12);
  EXPECT_NEAR(tf.colour(100.0)[0], 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(tf.denormalise(0.5), std::pow(10.0, 1.5), 1e-9);
  // Samples <= 0 (and below lo) map below the range: the first point.
  EXPECT_EQ(tf.normalise(0.0), 0.0);
  EXPECT_EQ(tf.normalise(-5.0), 0.0);
  EXPECT_EQ(tf.opacity(0.5), 0.0);
  EXPECT_EQ(tf.normalise(1e5), 1.0);
  // The GLSL map: normalised = log10(v) a + b.
  const auto m = tf.scaledValueMap();
  EXPECT_NEAR(std::log10(10.0) * m[0] + m[1], 1.0 / 3.0, 1e-12);
}

TEST(ValueScale, TableIsEvenInTheScale) {
  const TransferFunction tf = logRamp();
  const int n = 7;
  const std::vector<float> t = tf.bakeTable(n);
  for (int i = 0; i < n; ++i) {
    // Entry i stands for v = 10^(3 i / (n - 1)); the ramp's opacity there is i / (n - 1).
    const double x = double(i) / (n - 1);
    EXPECT_NEAR(t[4 * i + 0], x, 1e-6);
    EXPECT_NEAR(t[4 * i + 3], -std::log1p(-std::min(x, TransferFunction::kMaxOpacity)), 1e-5);
    EXPECT_NEAR(tf.normalise(std::pow(10.0, 3.0 * x)), x, 1e-12);
  }
}

TEST(ValueScale, SymlogTransferFunction) {
  const ValueScale s{ValueScaleKind::kSymlog, 1.0};
  const TransferFunction tf({{0.0, 0, 0, 0, 0}, {1.0, 1, 1, 1, 1}}, -100.0, 100.0, 1.0, s);
  const double c = 1.0 / 0.9, top = c + 2.0;  // s(100) = 1 * (c + log10(100))
  EXPECT_NEAR(tf.normalise(0.0), 0.5, 1e-12);
  EXPECT_NEAR(tf.normalise(1.0), 0.5 + 0.5 * c / top, 1e-12);
  EXPECT_NEAR(tf.normalise(-10.0), 0.5 - 0.5 * (c + 1.0) / top, 1e-12);
  EXPECT_NEAR(tf.denormalise(tf.normalise(-37.0)), -37.0, 1e-9);
}

// Blocks are classified by their min and max through the scale: opaque only above 100 (places
// 2/3 .. 1 of [1, 1000]).
TEST(ValueScale, BlockClassificationFollowsTheScale) {
  const TransferFunction tf({{0.0, 1, 1, 1, 0}, {2.0 / 3.0, 1, 1, 1, 0}, {1.0, 1, 1, 1, 1}}, 1.0, 1000.0, 1.0,
                            ValueScale{ValueScaleKind::kLog, 1.0});
  const int n = 256;
  EXPECT_FALSE(tf.tableSpanVisible(n, 1.0, 50.0));
  EXPECT_FALSE(tf.tableSpanVisible(n, -10.0, 0.0));  // <= 0: below the range
  EXPECT_FALSE(tf.tableSpanVisible(n, -10.0, 90.0));
  EXPECT_TRUE(tf.tableSpanVisible(n, 50.0, 150.0));
  EXPECT_TRUE(tf.tableSpanVisible(n, -1.0, 1e4));
  // A linear scale over the same range puts 150 at place 0.149: invisible.
  const TransferFunction lin(tf.points(), 1.0, 1000.0, 1.0);
  EXPECT_FALSE(lin.tableSpanVisible(n, 50.0, 150.0));
  // The adaptive step rule reads the same entries: a flat stretch (below 100) takes the largest
  // step, a block reaching into the ramp the smallest.
  const std::vector<float> table = tf.bakeTable(n);
  const StepRule rule(table, 1.0, 1000.0, 0.01, 0.001, 8, tf.scale());
  EXPECT_EQ(rule.level(2.0, 50.0), 3);
  EXPECT_EQ(rule.level(-5.0, 0.0), 3);
  EXPECT_EQ(rule.level(50.0, 900.0), 0);
}

// Pre-integration's segments go linearly in the scale: a constant segment at place x is the
// transfer function at x (closed form: D = tau L, C = c (1 - e^-D)).
TEST(ValueScale, PreintegrationIsOverScaledValues) {
  const TransferFunction tf = logRamp();
  const PreintegrationTable t = PreintegrationTable::build(tf, 16, 0.5);
  for (int i : {0, 5, 10, 15}) {
    const double x = double(i) / 15, tau = -std::log1p(-std::min(x, TransferFunction::kMaxOpacity));
    const double* e = &t.entries[4 * size_t(i + 16 * i)];
    EXPECT_NEAR(e[3], tau * 0.5, 1e-6) << i;
    EXPECT_NEAR(e[0], x * -std::expm1(-tau * 0.5), 1e-6) << i;
  }
  const TransferFunction lin(tf.points(), 1.0, 1000.0, 1.0);
  EXPECT_FALSE(sameTransferFunction(tf, lin));
}

TEST(ValueScale, LogRefusesARangeThroughZero) {
  std::string msg = inputErrorOf([] {
    parseScene(SceneText{"s.yaml", "transfer:\n  scale: log\n  range: [0, 10]\n"}, {});
  });
  EXPECT_NE(msg.find("'transfer.range': [0, 10]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("symlog"), std::string::npos) << msg;
  // transfer.range: auto against data through zero: at build time, with the data's range.
  const Scene s = parseScene(SceneText{"s.yaml", "transfer:\n  scale: log\n"}, {});
  msg = inputErrorOf([&] { s.transfer.build(0.0, 255.0, 1.0); });
  EXPECT_NE(msg.find("transfer.scale: log"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[0, 255]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("symlog"), std::string::npos) << msg;
  EXPECT_EQ(s.transfer.build(2.0, 255.0, 1.0).scale().kind, ValueScaleKind::kLog);
  msg = inputErrorOf([] { parseScene(SceneText{"s.yaml", "transfer:\n  scale: lg\n"}, {}); });
  EXPECT_NE(msg.find("transfer.scale"), std::string::npos) << msg;
  msg = inputErrorOf([] { parseScene(SceneText{"s.yaml", "transfer:\n  linear_width: 0\n"}, {}); });
  EXPECT_NE(msg.find("transfer.linear_width"), std::string::npos) << msg;
}

}  // namespace
}  // namespace sortlast
