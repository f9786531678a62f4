// Bricks of the grid (common/brick.h) and their assignment to ranks (common/decomposition.h).
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "common/brick.h"
#include "common/decomposition.h"
#include "common/error.h"
#include "common/grid.h"

namespace sortlast {
namespace {

bool bitEqual(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::string str(const glm::ivec3& v) {
  return "(" + std::to_string(v.x) + "," + std::to_string(v.y) + "," + std::to_string(v.z) + ")";
}

struct BrickCase {
  glm::ivec3 dims;
  glm::dvec3 spacing;
};

const std::vector<BrickCase>& brickCases() {
  static const std::vector<BrickCase> cases = {
      {{64, 64, 64}, {1.0, 1.0, 1.0}},
      {{65, 33, 17}, {0.7, 1.3, 0.1}},
      {{5, 5, 5}, {1.0, 2.0, 3.0}},
      {{2, 3, 9}, {0.3, 0.3, 0.3}},  // with d = 1 only (one cell along x)
  };
  return cases;
}

TEST(Bricks, CoverEveryCellExactlyOnce) {
  for (const BrickCase& bc : brickCases()) {
    GridGeometry grid{bc.dims, bc.spacing};
    for (int d = 1; d <= 4; ++d) {
      if (glm::any(glm::lessThan(bc.dims - 1, glm::ivec3(d)))) continue;
      SCOPED_TRACE("dims " + str(bc.dims) + " d " + std::to_string(d));
      auto bricks = makeBricks(grid, d);
      ASSERT_EQ(bricks.size(), size_t(d) * d * d);
      // Cells [lo, hi) per axis; count how often each cell is covered.
      glm::ivec3 cells = bc.dims - 1;
      std::vector<int> cover(size_t(cells.x) * cells.y * cells.z, 0);
      for (size_t i = 0; i < bricks.size(); ++i) {
        const Brick& b = bricks[i];
        EXPECT_EQ(b.id, int(i));
        EXPECT_EQ(b.id, b.cell.x + d * (b.cell.y + d * b.cell.z));
        for (int a = 0; a < 3; ++a) {
          ASSERT_GE(b.domain.lo[a], 0);
          ASSERT_LT(b.domain.lo[a], b.domain.hi[a]) << "brick " << i << " axis " << a;  // >= 1 cell
          ASSERT_LE(b.domain.hi[a], bc.dims[a] - 1);
        }
        for (int z = b.domain.lo.z; z < b.domain.hi.z; ++z)
          for (int y = b.domain.lo.y; y < b.domain.hi.y; ++y)
            for (int x = b.domain.lo.x; x < b.domain.hi.x; ++x)
              ++cover[x + size_t(cells.x) * (y + size_t(cells.y) * z)];
      }
      for (size_t c = 0; c < cover.size(); ++c) ASSERT_EQ(cover[c], 1) << "cell " << c;
      // Per axis, the cell ranges of the slabs partition [0, dims - 1) in cell order.
      for (int a = 0; a < 3; ++a) {
        int expect_lo = 0;
        for (int k = 0; k < d; ++k) {
          glm::ivec3 cell(0);
          cell[a] = k;
          const Brick& b = bricks[cell.x + d * (cell.y + d * cell.z)];
          EXPECT_EQ(b.domain.lo[a], expect_lo) << "axis " << a << " slab " << k;
          expect_lo = b.domain.hi[a];
        }
        EXPECT_EQ(expect_lo, bc.dims[a] - 1) << "axis " << a;
      }
    }
  }
}

TEST(Bricks, StoredIsDomainGrownByOneClamped) {
  for (const BrickCase& bc : brickCases()) {
    GridGeometry grid{bc.dims, bc.spacing};
    for (int d = 1; d <= 4; ++d) {
      if (glm::any(glm::lessThan(bc.dims - 1, glm::ivec3(d)))) continue;
      for (const Brick& b : makeBricks(grid, d))
        for (int a = 0; a < 3; ++a) {
          EXPECT_EQ(b.stored.lo[a], std::max(0, b.domain.lo[a] - 1)) << "brick " << b.id << " axis " << a;
          EXPECT_EQ(b.stored.hi[a], std::min(bc.dims[a] - 1, b.domain.hi[a] + 1)) << "brick " << b.id << " axis " << a;
          // Interior faces do have a ghost layer.
          if (b.cell[a] > 0) { EXPECT_EQ(b.stored.lo[a], b.domain.lo[a] - 1); }
          if (b.cell[a] < d - 1) { EXPECT_EQ(b.stored.hi[a], b.domain.hi[a] + 1); }
        }
    }
  }
}

TEST(Bricks, WorldBoxesShareFacesBitwise) {
  for (const BrickCase& bc : brickCases()) {
    GridGeometry grid{bc.dims, bc.spacing};
    Box3 whole = grid.worldBox();
    for (int d = 1; d <= 4; ++d) {
      if (glm::any(glm::lessThan(bc.dims - 1, glm::ivec3(d)))) continue;
      SCOPED_TRACE("dims " + str(bc.dims) + " d " + std::to_string(d));
      auto bricks = makeBricks(grid, d);
      for (const Brick& b : bricks) {
        Box3 want = grid.worldBoxOf(b.domain);
        for (int a = 0; a < 3; ++a) {
          EXPECT_TRUE(bitEqual(b.world.lo[a], want.lo[a])) << "brick " << b.id << " axis " << a;
          EXPECT_TRUE(bitEqual(b.world.hi[a], want.hi[a])) << "brick " << b.id << " axis " << a;
          EXPECT_LT(b.world.lo[a], b.world.hi[a]);
          if (b.cell[a] == 0) { EXPECT_TRUE(bitEqual(b.world.lo[a], whole.lo[a])); }
          if (b.cell[a] == d - 1) { EXPECT_TRUE(bitEqual(b.world.hi[a], whole.hi[a])); }
          if (b.cell[a] + 1 < d) {
            glm::ivec3 nc = b.cell;
            ++nc[a];
            const Brick& n = bricks[nc.x + d * (nc.y + d * nc.z)];
            EXPECT_TRUE(bitEqual(b.world.hi[a], n.world.lo[a]))
                << "bricks " << b.id << " and " << n.id << " axis " << a << ": " << b.world.hi[a]
                << " vs " << n.world.lo[a];
            // The other two axes line up exactly too.
            for (int o = 0; o < 3; ++o)
              if (o != a) {
                EXPECT_TRUE(bitEqual(b.world.lo[o], n.world.lo[o]));
                EXPECT_TRUE(bitEqual(b.world.hi[o], n.world.hi[o]));
              }
          }
        }
      }
    }
  }
}

TEST(Bricks, TooManyBricksPerAxisThrows) {
  EXPECT_THROW(makeBricks(GridGeometry{{5, 5, 5}, glm::dvec3(1.0)}, 5), InputError);
  EXPECT_NO_THROW(makeBricks(GridGeometry{{5, 5, 5}, glm::dvec3(1.0)}, 4));
  EXPECT_THROW(makeBricks(GridGeometry{{65, 33, 17}, glm::dvec3(1.0)}, 17), InputError);  // z: 16 cells
  EXPECT_NO_THROW(makeBricks(GridGeometry{{65, 33, 17}, glm::dvec3(1.0)}, 16));
  EXPECT_THROW(makeBricks(GridGeometry{{64, 64, 64}, glm::dvec3(1.0)}, 64), InputError);
  EXPECT_THROW(makeBricks(GridGeometry{{2, 3, 9}, glm::dvec3(1.0)}, 2), InputError);  // x: 1 cell
  EXPECT_THROW(makeBricks(GridGeometry{{8, 8, 8}, glm::dvec3(1.0)}, 0), InputError);
}

TEST(Assignment, EveryBrickOneOwnerAndConvexDisjointRegions) {
  for (int d = 1; d <= 4; ++d)
    for (int P = 1; P <= 8; ++P) {
      SCOPED_TRACE("d " + std::to_string(d) + " P " + std::to_string(P));
      Assignment as = assignBricks(d, P);
      const int n = d * d * d;
      ASSERT_EQ(as.owner.size(), size_t(n));
      ASSERT_EQ(as.region.size(), size_t(P));
      for (int i = 0; i < n; ++i) {
        EXPECT_GE(as.owner[i], 0) << "brick " << i;
        EXPECT_LT(as.owner[i], P) << "brick " << i;
      }
      int ranks_with_bricks = 0;
      long long total = 0;
      for (int r = 0; r < P; ++r) {
        const IndexBox& reg = as.region[r];
        auto ids = as.bricksOf(r);
        // bricksOf agrees with owner.
        for (int id : ids) EXPECT_EQ(as.owner[id], r);
        long long owned = 0;
        for (int i = 0; i < n; ++i) owned += as.owner[i] == r;
        EXPECT_EQ(owned, (long long)ids.size()) << "rank " << r;
        // Exactly its region box: the count equals the box volume and every brick is inside.
        EXPECT_EQ(reg.count(), (long long)ids.size()) << "rank " << r;
        for (int id : ids) {
          glm::ivec3 c(id % d, (id / d) % d, id / (d * d));
          for (int a = 0; a < 3; ++a) {
            EXPECT_GE(c[a], reg.lo[a]) << "rank " << r << " brick " << id;
            EXPECT_LE(c[a], reg.hi[a]) << "rank " << r << " brick " << id;
          }
        }
        if (reg.count() > 0)
          for (int a = 0; a < 3; ++a) {
            EXPECT_GE(reg.lo[a], 0);
            EXPECT_LT(reg.hi[a], d);
          }
        total += reg.count();
        ranks_with_bricks += !ids.empty();
      }
      EXPECT_EQ(total, n);
      // Regions are pairwise disjoint.
      for (int r = 0; r < P; ++r)
        for (int s = r + 1; s < P; ++s) {
          const IndexBox &A = as.region[r], &B = as.region[s];
          if (A.count() == 0 || B.count() == 0) continue;
          EXPECT_EQ(intersect(A, B).count(), 0)
              << "regions of ranks " << r << " and " << s << " overlap";
        }
      // Only ranks beyond the number of bricks own nothing.
      EXPECT_EQ(ranks_with_bricks, std::min(P, n));
    }
}

}  // namespace
}  // namespace sortlast
