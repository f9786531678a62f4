// The blocks a brick draws (adaptive/adaptive_brick.h): its cells tile the brick along the block
// planes, and the shader's lookup on the brick's own atlas (sampleCell) is the whole volume's
// adaptive field (sampleIndex) in every cell, for bricks whose faces fall on block planes and
// bricks that cut blocks.
#include "adaptive/adaptive_brick.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "common/brick.h"

namespace sortlast {
namespace {

// A smooth background with a thin oblique sheet and a step (the crack test's volume of
// adaptive_blocks_test): blocks at several levels side by side. Dims not 2^k + 1: padded blocks.
struct Volume {
  GridGeometry grid;
  std::vector<float> v;
};
Volume sheetAndStep(const glm::ivec3& dims) {
  Volume t{{dims, {1.0, 1.0, 1.0}}, {}};
  const glm::dvec3 n = glm::normalize(glm::dvec3(1.0, 0.7, 0.4));
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        glm::dvec3 q(x, y, z);
        double v = 0.2 + 0.1 * std::sin(q.x / 20.0) * std::cos(q.y / 25.0);
        if (std::abs(glm::dot(n, q - glm::dvec3(30.0, 28.0, 33.0))) < 0.8) v += 1.0;
        if (q.x > 40.3 && q.y < 30.0) v += 0.5;
        t.v.push_back(float(v));
      }
  return t;
}

TEST(AdaptiveBrick, CellsTileTheBrickAlongBlockPlanes) {
  const Volume t = sheetAndStep({61, 57, 66});
  const AdaptiveVolume a = buildAdaptive(t.grid, t.v, {8, 0.05, 2});
  const BlockGrid& g = a.blocks;
  for (int d : {1, 2, 3, 5}) {
    for (const Brick& brick : makeBricks(t.grid, d)) {
      SCOPED_TRACE("d = " + std::to_string(d) + ", brick " + std::to_string(brick.id));
      const AdaptiveBrickBlocks b = adaptiveBrickBlocks(a, brick.domain);
      ASSERT_EQ(b.table.size(), size_t(b.count.x) * b.count.y * b.count.z);
      for (int ax = 0; ax < 3; ++ax) {
        const std::vector<int>& p = b.planes[ax];
        ASSERT_EQ(p.size(), size_t(b.count[ax]) + 1);
        EXPECT_EQ(p.front(), brick.domain.lo[ax]);
        EXPECT_EQ(p.back(), brick.domain.hi[ax]);
        for (size_t i = 0; i + 1 < p.size(); ++i) {
          EXPECT_LT(p[i], p[i + 1]);
          // Cell i lies inside block first + i.
          const int block = b.first[ax] + int(i);
          EXPECT_GE(p[i], block * g.block_cells[ax]);
          EXPECT_LE(p[i + 1], (block + 1) * g.block_cells[ax]);
        }
      }
      for (int id = 0; id < int(b.table.size()); ++id) {
        const glm::ivec3 cell(id % b.count.x, (id / b.count.x) % b.count.y,
                              id / (b.count.x * b.count.y));
        const AdaptiveBlock& whole = a.table[size_t(g.id(b.first + cell))];
        EXPECT_EQ(b.table[size_t(id)].level, whole.level);
        EXPECT_EQ(b.table[size_t(id)].vmin, whole.vmin);
        EXPECT_EQ(b.table[size_t(id)].vmax, whole.vmax);
      }
    }
  }
}

TEST(AdaptiveBrick, LookupIsTheVolumesField) {
  const Volume t = sheetAndStep({61, 57, 66});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (double tol : {0.02, 0.1}) {
    const AdaptiveVolume a = buildAdaptive(t.grid, t.v, {8, tol, 2});
    const BlockGrid& g = a.blocks;
    int levels_seen = 0;
    for (int d : {1, 3}) {
      for (const Brick& brick : makeBricks(t.grid, d)) {
        SCOPED_TRACE("tolerance " + std::to_string(tol) + ", d = " + std::to_string(d) +
                     ", brick " + std::to_string(brick.id));
        const AdaptiveBrickBlocks b = adaptiveBrickBlocks(a, brick.domain);
        for (int id = 0; id < int(b.table.size()); ++id) {
          const glm::ivec3 cell(id % b.count.x, (id / b.count.x) % b.count.y,
                                id / (b.count.x * b.count.y));
          levels_seen |= 1 << b.table[size_t(id)].level;
          const IndexBox block = g.samplesOf(b.first + cell);
          const glm::dvec3 lo(block.lo), hi(glm::min(block.hi, g.dims - 1));
          for (int k = 0; k < 40; ++k) {
            // Inside the block's box (the whole block: a brick reads beyond its faces there):
            // exactly the volume's field, away from the faces other blocks share.
            glm::dvec3 u = lo + glm::dvec3(unit(rng), unit(rng), unit(rng)) * (hi - lo);
            u = glm::clamp(u, lo + 1e-3, hi - 1e-3);
            EXPECT_EQ(sampleCell(b, cell, u), sampleIndex(a, u));
            // On its faces and corners: the neighbour's value up to the float rounding of
            // stitched samples (the field is O(1)).
            glm::dvec3 f = u;
            f[k % 3] = (k & 4) ? hi[k % 3] : lo[k % 3];
            EXPECT_NEAR(sampleCell(b, cell, f), sampleIndex(a, f), 1e-6);
            // Beyond the block (a coarse sample before a cell's entry): the block's value at the
            // nearest point of its box.
            glm::dvec3 out = u;
            out[k % 3] += ((k & 8) ? 1.0 : -1.0) * (1.0 + 4.0 * unit(rng));
            EXPECT_EQ(sampleCell(b, cell, out), sampleCell(b, cell, glm::clamp(out, lo, glm::dvec3(block.hi))));
          }
        }
      }
    }
    EXPECT_GE(__builtin_popcount(unsigned(levels_seen)), 2) << "only one level in use: vacuous";
  }
}

}  // namespace
}  // namespace sortlast
