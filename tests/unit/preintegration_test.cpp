// Pre-integrated transfer-function tables (transfer/preintegration.h) against an independent direct
// integration of the emission-absorption model along linear segments, in double.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "transfer/preintegration.h"
#include "transfer/transfer_function.h"

namespace sortlast {
namespace {

// Front-to-back midpoint rule with `steps` substeps on the transfer function itself: the value
// goes linearly from normalised xf to xb over `length`. Premultiplied (r, g, b, alpha).
std::array<double, 4> direct(const TransferFunction& tf, double xf, double xb, double length,
                             int steps = 4000) {
  double rgb[3] = {0, 0, 0}, transmit = 1.0;
  const double h = length / steps, span = tf.rangeHi() - tf.rangeLo();
  for (int m = 0; m < steps; ++m) {
    const double x = xf + (xb - xf) * (m + 0.5) / steps;
    const double v = tf.rangeLo() + x * span;
    const double a = -std::expm1(-tf.extinction(v) * h);
    auto c = tf.colour(v);
    for (int k = 0; k < 3; ++k) rgb[k] += transmit * a * c[k];
    transmit *= 1.0 - a;
  }
  return {rgb[0], rgb[1], rgb[2], 1.0 - transmit};
}

double maxDiff(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  double m = 0.0;
  for (int k = 0; k < 4; ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

// The presets the tests render: neghip's sharp band (tests/data/neghip.yaml) and the default.
TransferFunction sharp() { return TransferFunction(TransferFunction::preset("sharp"), 0.0, 255.0, 1.0); }
TransferFunction soft() { return TransferFunction(TransferFunction::preset("default"), 0.0, 1.0, 1.0); }

// Largest error over random segments, per kind: at table nodes (the integration alone), at any
// values (plus the bilinear filter), and at other lengths (plus the length correction), opacity
// and colour apart.
struct Errors {
  double node = 0, any = 0, length_alpha = 0, length_colour = 0;
};
Errors measure(const TransferFunction& tf, const PreintegrationTable& t, double max_ratio) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Errors e;
  const int n = t.n;
  for (int it = 0; it < 150; ++it) {
    const double xi = std::min(n - 1, int(u(rng) * n)) / double(n - 1);
    const double xj = std::min(n - 1, int(u(rng) * n)) / double(n - 1);
    e.node = std::max(e.node, maxDiff(t.lookup(xi, xj, t.base_length), direct(tf, xi, xj, t.base_length)));
    const double xf = u(rng), xb = u(rng);
    e.any = std::max(e.any, maxDiff(t.lookup(xf, xb, t.base_length), direct(tf, xf, xb, t.base_length)));
    const double L = t.base_length * (1.0 + (max_ratio - 1.0) * u(rng));
    auto a = t.lookup(xi, xj, L), b = direct(tf, xi, xj, L);
    e.length_alpha = std::max(e.length_alpha, std::abs(a[3] - b[3]));
    for (int k = 0; k < 3; ++k) e.length_colour = std::max(e.length_colour, std::abs(a[k] - b[k]));
  }
  return e;
}

// Measured on this machine (150 random segments each; the worst of L0 = 0.5, 1, 2 voxels with unit
// length 1 voxel, so a segment of the sharp band reaches opacity 1 - 0.1^2): nodes 1.4e-4, any
// values 1.7e-3 (0.44/255; the filter between entries 1/255 apart on a band 0.1 wide), other
// lengths up to 1.2 L0 (slicing: ds = spacing / cos, cos >= 0.83 at a 45-degree field of view's
// corners) opacity 2.2e-6 (at nodes the correction is exact for the opacity: this is the direct
// integrator's own error at 4,000 steps; 7.7e-8 at 20,000) and colour
// 1.3e-2 (the colour scaled by the opacities' ratio, worst on a segment crossing the whole
// range in 2 voxels: 0 -> 1 under the default preset). Bounds: about 2x the measured values.
TEST(Preintegration, MatchesDirectIntegration) {
  for (const TransferFunction& tf : {sharp(), soft()}) {
    for (double L0 : {0.5, 1.0, 2.0}) {
      const auto t0 = std::chrono::steady_clock::now();
      const PreintegrationTable t = PreintegrationTable::build(tf, PreintegrationTable::kDefaultSize, L0);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      const Errors e = measure(tf, t, 1.2);
      std::printf("L0 %.1f: build %.1f ms; max error: nodes %.2e, any values %.2e, length x1.2: "
                  "alpha %.2e, colour %.2e\n", L0, ms, e.node, e.any, e.length_alpha, e.length_colour);
      EXPECT_LT(e.node, 3e-4);
      EXPECT_LT(e.any, 3.5e-3);
      EXPECT_LT(e.length_alpha, 1e-5);
      EXPECT_LT(e.length_colour, 2.5e-2);
      EXPECT_LT(ms, 2000.0);  // measured 26-38 ms; rebuilt on every change of the function or step
    }
  }
}

// The length correction leaves opacity exact: at a table node (no filter error) the alpha of any
// length is the direct integral's within the node error.
TEST(Preintegration, OpacityCorrectionForOtherLengths) {
  const TransferFunction tf = sharp();
  const PreintegrationTable t = PreintegrationTable::build(tf, 256, 1.0);
  for (double L : {0.25, 0.5, 1.7, 3.0})
    for (auto [i, j] : {std::pair{100, 140}, {128, 128}, {140, 100}, {120, 131}}) {
      auto a = t.lookup(i / 255.0, j / 255.0, L), b = direct(tf, i / 255.0, j / 255.0, L);
      EXPECT_NEAR(a[3], b[3], 3e-4 * std::max(1.0, L)) << "L " << L << " i " << i << " j " << j;
    }
}

// A constant segment is the midpoint rule's sample: c(v) (1 - exp(-tau(v) L0)), exactly up to
// double rounding at the table's nodes; between nodes the filter mixes segments between the two
// neighbouring values: measured 2.4e-2 on the sharp band, at its peak, where the opacity's slope
// jumps from +18 to -18 per unit value and the filter cuts the corner between entries 1/255 apart
// (the 1D table of the midpoint rule has 4096 entries there, 16 times finer). Rendered images do
// not change measurably with 1024 entries (tests/mpi/preintegration.sh), so 256 it is.
TEST(Preintegration, ConstantSegmentsAreTheMidpointRule) {
  const TransferFunction tf = sharp();
  const double L0 = 1.0;
  const PreintegrationTable t = PreintegrationTable::build(tf, 256, L0);
  for (int i = 0; i < 256; ++i) {
    const double v = 255.0 * i / 255.0;
    const double a = 1.0 - std::exp(-tf.extinction(v) * L0);
    auto c = tf.colour(v);
    auto e = t.lookup(i / 255.0, i / 255.0, L0);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(e[k], c[k] * a, 1e-14) << i;
    EXPECT_NEAR(e[3], a, 1e-14) << i;
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  for (int it = 0; it < 2000; ++it) {
    const double x = u(rng);
    const double a = 1.0 - std::exp(-tf.extinction(255.0 * x) * L0);
    auto c = tf.colour(255.0 * x);
    worst = std::max(worst, maxDiff(t.lookup(x, x, L0), {c[0] * a, c[1] * a, c[2] * a, a}));
  }
  EXPECT_LT(worst, 4e-2);
}

// Empty-space skipping relies on this: entries between values of zero opacity are exactly zero.
TEST(Preintegration, TransparentValuesGiveExactlyZero) {
  const TransferFunction tf = sharp();  // zero opacity below 0.45
  const PreintegrationTable t = PreintegrationTable::build(tf, 256, 2.0);
  for (int i = 0; i < 114; ++i)    // 114 / 255 < 0.45
    for (int j = 0; j < 114; ++j)
      for (int k = 0; k < 4; ++k) ASSERT_EQ(t.entries[size_t(4) * (i + 256 * j) + k], 0.0) << i << " " << j;
  // And one entry reaching into the band is not.
  EXPECT_GT(t.entries[size_t(4) * (100 + 256 * 128) + 3], 0.0);
}

}  // namespace
}  // namespace sortlast
