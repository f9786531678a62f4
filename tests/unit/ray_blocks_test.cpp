// The ray caster's block classification (render/volume/ray_blocks.h, render/volume/step_rule.h): the distance a
// ray may jump from an empty block, and the step multiple a block's range allows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "transfer/transfer_function.h"
#include "render/volume/ray_blocks.h"
#include "render/volume/step_rule.h"

namespace sortlast {
namespace {

TEST(RayBlocks, ChessboardDistanceIsTheBruteForceOne) {
  const glm::ivec3 n(9, 7, 5);
  uint32_t s = 7;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<unsigned char> vis(size_t(n.x * n.y * n.z));
    for (auto& v : vis) {
      s = s * 1664525u + 1013904223u;
      v = (s >> 24) < unsigned(trial) ? 1 : 0;  // from none visible to ~8 % visible
    }
    auto d = chessboardDistance(n, vis);
    for (int z = 0; z < n.z; ++z)
      for (int y = 0; y < n.y; ++y)
        for (int x = 0; x < n.x; ++x) {
          int best = 255;
          for (int w = 0; w < n.z; ++w)
            for (int v = 0; v < n.y; ++v)
              for (int u = 0; u < n.x; ++u)
                if (vis[size_t(u + n.x * (v + n.y * w))])
                  best = std::min(best, std::max({std::abs(u - x), std::abs(v - y), std::abs(w - z)}));
          ASSERT_EQ(int(d[size_t(x + n.x * (y + n.y * z))]), best) << x << " " << y << " " << z;
        }
  }
}

TEST(RayBlocks, ClassReachIsTheDistanceToAnotherClass) {
  const glm::ivec3 n(8, 6, 5);
  uint32_t s = 99;
  std::vector<unsigned char> cls(size_t(n.x * n.y * n.z));
  for (auto& c : cls) {
    s = s * 1664525u + 1013904223u;
    c = (s >> 24) < 240 ? 0 : (unsigned char)(1 + (s >> 8) % 3);  // mostly empty, three classes
  }
  auto r = classReach(n, cls);
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        const unsigned char c = cls[size_t(x + n.x * (y + n.y * z))];
        int best = 255;
        for (int w = 0; w < n.z; ++w)
          for (int v = 0; v < n.y; ++v)
            for (int u = 0; u < n.x; ++u)
              if (cls[size_t(u + n.x * (v + n.y * w))] != c)
                best = std::min(best, std::max({std::abs(u - x), std::abs(v - y), std::abs(w - z)}));
        ASSERT_EQ(int(r[size_t(x + n.x * (y + n.y * z))]), best) << x << " " << y << " " << z;
      }
}

TEST(RayBlocks, BricksCutTheVolumeGridAtItsPlanes) {
  GridGeometry grid{{30, 20, 12}, {1.0, 1.0, 2.0}};
  auto bricks = makeBricks(grid, 2);
  RayBlockGrid rg = rayBlockGrid(grid, 8);
  EXPECT_EQ(rg.count, glm::ivec3(4, 3, 2));  // 29, 19, 11 cells
  std::vector<float> samples;
  for (const Brick& b : bricks) {
    samples.assign(size_t(b.stored.count()), 0.0f);
    size_t i = 0;
    for (int z = b.stored.lo.z; z <= b.stored.hi.z; ++z)
      for (int y = b.stored.lo.y; y <= b.stored.hi.y; ++y)
        for (int x = b.stored.lo.x; x <= b.stored.hi.x; ++x) samples[i++] = float(x + 100 * y + 10000 * z);
    BrickBlocks bb = cutBrickBlocks(b, grid, FloatBrickSamples(samples, b.stored), rg);
    for (int a = 0; a < 3; ++a) {
      // Planes: the brick's faces and the multiples of 8 between them.
      EXPECT_DOUBLE_EQ(bb.planes[a].front(), b.world.lo[a]);
      EXPECT_DOUBLE_EQ(bb.planes[a].back(), b.world.hi[a]);
      for (size_t k = 1; k + 1 < bb.planes[a].size(); ++k) {
        double idx = grid.indexOfWorld(glm::dvec3(bb.planes[a][k]))[a];
        EXPECT_NEAR(std::fmod(idx, 8.0), 0.0, 1e-9);
      }
    }
    // The cut block's range covers its samples inside the brick; the grown one one sample more.
    const size_t first = 0;
    EXPECT_EQ(bb.vmin[first], float(b.domain.lo.x + 100 * b.domain.lo.y + 10000 * b.domain.lo.z));
    EXPECT_EQ(bb.grown_min[first], float(std::max(b.stored.lo.x, bb.first.x * 8 - 1) +
                                         100 * std::max(b.stored.lo.y, bb.first.y * 8 - 1) +
                                         10000 * std::max(b.stored.lo.z, bb.first.z * 8 - 1)));
  }
}

TEST(StepRule, TakesTheLargestMultipleWithinTheBound) {
  // tau rises steeply over [0.4, 0.5] and is flat (opaque) above 0.6.
  TransferFunction tf({{0.0, 0, 0, 0, 0}, {0.4, 1, 0, 0, 0}, {0.5, 0, 1, 0, 0.9}, {0.6, 0, 0, 1, 0.9},
                       {1.0, 0, 0, 1, 0.9}},
                      0.0, 100.0, 1.0);
  const std::vector<float> table = tf.bakeTable(256);
  const double delta = 0.25, tol = 0.05;
  StepRule rule(table, 0.0, 100.0, delta, tol, StepRule::maxMultiple(delta, 1.0));
  EXPECT_EQ(StepRule::maxMultiple(delta, 1.0), 8);
  EXPECT_EQ(StepRule::maxMultiple(0.5, 1.0), 4);
  EXPECT_EQ(StepRule::maxMultiple(1.0, 1.0), 2);
  EXPECT_EQ(StepRule::maxMultiple(3.0, 1.0), 1);
  EXPECT_EQ(rule.level(65.0f, 95.0f), 3);  // flat: m = 8 though opaque
  EXPECT_EQ(rule.level(10.0f, 20.0f), 3);  // transparent
  EXPECT_EQ(rule.level(40.0f, 50.0f), 0);  // the steep ramp
  // Against a scan of the entries: m delta osc <= tol for the chosen m, > tol for 2m (below the cap).
  for (float lo = 0.0f; lo < 100.0f; lo += 3.7f)
    for (float w = 0.0f; lo + w <= 100.0f; w += 5.3f) {
      const int i0 = int(std::floor(lo / 100.0 * 255)), i1 = int(std::ceil((lo + w) / 100.0 * 255));
      double osc = 0.0;
      for (int c = 0; c < 4; ++c) {
        double mn = 1e30, mx = -1e30;
        for (int i = i0; i <= i1; ++i) {
          double v = c == 3 ? table[4 * i + 3] : table[4 * i + c] * table[4 * i + 3];
          mn = std::min(mn, v);
          mx = std::max(mx, v);
        }
        osc = std::max(osc, mx - mn);
      }
      const int j = rule.level(lo, lo + w), m = 1 << j;
      if (j > 0) EXPECT_LE(m * delta * osc, tol * (1 + 1e-6)) << lo << " " << w;
      if (j < 3) EXPECT_GT(2 * m * delta * osc, tol * (1 - 1e-6)) << lo << " " << w;
    }
}

}  // namespace
}  // namespace sortlast
