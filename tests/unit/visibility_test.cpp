// Back-to-front brick order (common/visibility.h), checked against ray casting: along every
// ray from the eye, a brick the ray enters later must come earlier in the order.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <string>
#include <vector>

#include "common/box.h"
#include "common/brick_planes.h"
#include "common/decomposition.h"
#include "common/visibility.h"

namespace sortlast {
namespace {

using Planes = std::array<std::vector<double>, 3>;

// Three coordinates per axis region: below the grid, inside it, above it. "Inside" includes points
// exactly on the grid's planes (inner and outer).
std::vector<double> sampleCoords(const std::vector<double>& p, int region, std::mt19937& rng) {
  double lo = p.front(), hi = p.back(), ext = hi - lo;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  switch (region) {
    case 0: return {lo - 0.3 * ext, lo - 2.0 * ext, lo - ext * (0.01 + u(rng))};
    case 2: return {hi + 0.3 * ext, hi + 2.0 * ext, hi + ext * (0.01 + u(rng))};
    default: {
      std::vector<double> v = {lo, hi, p[p.size() / 2], lo + ext * u(rng), lo + ext * u(rng)};
      if (p.size() > 2) v.push_back(p[1]);
      return v;
    }
  }
}

// Checks `order` against `rays` rays from `eye`. Returns a description of the first violation, or
// an empty string.
std::string checkOrder(const Planes& planes, const glm::dvec3& eye, int rays, std::mt19937& rng) {
  const int dx = int(planes[0].size()) - 1, dy = int(planes[1].size()) - 1, dz = int(planes[2].size()) - 1;
  const int n = dx * dy * dz;
  std::vector<int> order = backToFrontOrder(planes, eye);
  if (int(order.size()) != n) return "order has " + std::to_string(order.size()) + " entries, want " + std::to_string(n);
  std::vector<int> pos(n, -1);
  for (int i = 0; i < n; ++i) {
    if (order[i] < 0 || order[i] >= n || pos[order[i]] != -1) return "order is not a permutation";
    pos[order[i]] = i;
  }
  std::vector<Box3> boxes(n);
  for (int z = 0; z < dz; ++z)
    for (int y = 0; y < dy; ++y)
      for (int x = 0; x < dx; ++x)
        boxes[x + dx * (y + dy * z)] = {{planes[0][x], planes[1][y], planes[2][z]},
                                        {planes[0][x + 1], planes[1][y + 1], planes[2][z + 1]}};
  Box3 all{{planes[0].front(), planes[1].front(), planes[2].front()},
           {planes[0].back(), planes[1].back(), planes[2].back()}};
  glm::dvec3 ext = all.extent();
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  std::vector<std::pair<double, int>> hits;  // entry distance, brick
  for (int r = 0; r < rays; ++r) {
    glm::dvec3 dir;
    if (r % 2 == 0) {
      // Aim at a random point of (a slightly grown) grid box, so most rays hit something.
      glm::dvec3 target = all.lo + glm::dvec3(u(rng), u(rng), u(rng)) * ext;
      dir = target - eye;
      if (glm::length(dir) < 1e-12) continue;
    } else {
      dir = {gauss(rng), gauss(rng), gauss(rng)};
    }
    dir = glm::normalize(dir);
    hits.clear();
    for (int b = 0; b < n; ++b) {
      double t0, t1;
      if (!intersectRayBox(eye, dir, boxes[b], t0, t1)) continue;
      double entry = std::max(t0, 0.0);
      if (t1 - entry <= 1e-9) continue;  // missed, behind the eye, or only touched
      hits.push_back({entry, b});
    }
    std::sort(hits.begin(), hits.end());
    for (size_t i = 0; i < hits.size(); ++i)
      for (size_t j = i + 1; j < hits.size(); ++j) {
        if (hits[j].first - hits[i].first <= 1e-9) continue;  // entered together: no constraint
        // hits[j] is farther along the ray: it must be drawn first.
        if (pos[hits[j].second] > pos[hits[i].second])
          return "ray " + std::to_string(r) + " dir (" + std::to_string(dir.x) + ", " +
                 std::to_string(dir.y) + ", " + std::to_string(dir.z) + "): brick " +
                 std::to_string(hits[j].second) + " (entry " + std::to_string(hits[j].first) +
                 ") is drawn after brick " + std::to_string(hits[i].second) + " (entry " +
                 std::to_string(hits[i].first) + ")";
      }
  }
  return "";
}

void checkAllRegions(const Planes& planes, unsigned seed) {
  std::mt19937 rng(seed);
  int eyes = 0;
  for (int rz = 0; rz < 3; ++rz)
    for (int ry = 0; ry < 3; ++ry)
      for (int rx = 0; rx < 3; ++rx) {
        auto xs = sampleCoords(planes[0], rx, rng), ys = sampleCoords(planes[1], ry, rng),
             zs = sampleCoords(planes[2], rz, rng);
        // Several eyes per region: pair the candidate coordinates up (cycling the shorter lists).
        size_t m = std::max({xs.size(), ys.size(), zs.size()});
        for (size_t i = 0; i < m; ++i) {
          glm::dvec3 eye(xs[i % xs.size()], ys[(i + 1) % ys.size()], zs[(i + 2) % zs.size()]);
          std::string err = checkOrder(planes, eye, 2000, rng);
          ASSERT_EQ(err, "") << "region (" << rx << "," << ry << "," << rz << ") eye (" << eye.x
                             << ", " << eye.y << ", " << eye.z << ")";
          ++eyes;
        }
      }
  EXPECT_GE(eyes, 27 * 3);
}

std::vector<double> uniformPlanes(int d, double lo, double hi) {
  std::vector<double> p;
  for (int i = 0; i <= d; ++i) p.push_back(lo + (hi - lo) * i / d);
  return p;
}

TEST(Visibility, Grid3x3x3AllRegions) {
  checkAllRegions({uniformPlanes(3, -1.5, 1.5), uniformPlanes(3, -1.5, 1.5), uniformPlanes(3, -1.5, 1.5)}, 11);
}

TEST(Visibility, Grid2x2x2AllRegions) {
  checkAllRegions({uniformPlanes(2, -1, 1), uniformPlanes(2, -0.5, 0.5), uniformPlanes(2, 0, 4)}, 12);
}

TEST(Visibility, IrregularGrid4x1x3AllRegions) {
  checkAllRegions({std::vector<double>{-2.0, -1.7, 0.1, 0.15, 3.0}, std::vector<double>{-0.4, 0.9},
                   std::vector<double>{0.0, 2.5, 2.75, 6.0}},
                  13);
}

TEST(Visibility, CellIndexLayoutIsXFastest) {
  // Eye far beyond the high corner in x, below in y and z: the farthest brick is (0, dy-1, dz-1).
  Planes planes = {std::vector<double>{0, 1, 2, 3, 4}, std::vector<double>{0, 1}, std::vector<double>{0, 1, 2, 3}};
  auto order = backToFrontOrder(planes, {10.0, -10.0, -10.0});
  ASSERT_EQ(order.size(), 12u);
  EXPECT_EQ(order.front(), 0 + 4 * (0 + 1 * 2));
  EXPECT_EQ(order.back(), 3 + 4 * (0 + 1 * 0));
}

TEST(Visibility, SlabOrderHandCases) {
  std::vector<double> p = {0.0, 1.0, 2.0, 3.0, 4.0};
  EXPECT_EQ(slabOrder(p, -5.0), (std::vector<int>{3, 2, 1, 0}));   // below: highest first
  EXPECT_EQ(slabOrder(p, 9.0), (std::vector<int>{0, 1, 2, 3}));    // above: lowest first
  EXPECT_EQ(slabOrder(p, 0.5), (std::vector<int>{3, 2, 1, 0}));    // inside slab 0: it is last
  EXPECT_EQ(slabOrder(p, 3.5), (std::vector<int>{0, 1, 2, 3}));    // inside slab 3: it is last
  // Inside slab 1: slab 3 is the farthest, slabs 0 and 2 are equally far (either order), 1 last.
  auto o = slabOrder(p, 1.5);
  ASSERT_EQ(o.size(), 4u);
  EXPECT_EQ(o[0], 3);
  EXPECT_EQ(o[3], 1);
  EXPECT_TRUE((o[1] == 0 && o[2] == 2) || (o[1] == 2 && o[2] == 0));
  // Eye on the inner plane 2.0: slabs 1 and 2 both touch it and come last; 3 and 0 are farther.
  o = slabOrder(p, 2.0);
  ASSERT_EQ(o.size(), 4u);
  std::vector<int> last2 = {o[2], o[3]}, first2 = {o[0], o[1]};
  std::sort(last2.begin(), last2.end());
  std::sort(first2.begin(), first2.end());
  EXPECT_EQ(last2, (std::vector<int>{1, 2}));
  EXPECT_EQ(first2, (std::vector<int>{0, 3}));
  // Irregular planes, eye inside slab 2 at 0.12: distances 0: 0.22, 1: 0.02, 3: 0.03.
  std::vector<double> q = {-2.0, -0.1, 0.1, 0.15, 3.0};
  EXPECT_EQ(slabOrder(q, 0.12), (std::vector<int>{0, 3, 1, 2}));
  // One slab.
  EXPECT_EQ(slabOrder({0.0, 1.0}, 0.5), (std::vector<int>{0}));
  EXPECT_EQ(slabOrder({0.0, 1.0}, -3.0), (std::vector<int>{0}));
}

// The rank order (a traversal of the kd-split tree) against ray casting through the rank regions,
// for every rank count 1-8 and d = 1-4, eyes around, on and inside irregular grids.
TEST(Visibility, RankOrderAgreesWithRays) {
  std::mt19937 rng(14);
  for (int d = 1; d <= 4; ++d) {
    Planes planes;
    std::uniform_real_distribution<double> gap(0.2, 2.0);
    for (int a = 0; a < 3; ++a) {
      planes[a].push_back(-3.0 + a);
      for (int i = 0; i < d; ++i) planes[a].push_back(planes[a].back() + gap(rng));
    }
    for (int P = 1; P <= 8; ++P) {
      SCOPED_TRACE("d " + std::to_string(d) + " P " + std::to_string(P));
      Assignment as = assignBricks(d, P);
      std::vector<Box3> boxes;
      for (int r = 0; r < P; ++r) boxes.push_back(cellRangeBox(planes, as.region[size_t(r)]));
      Box3 all = cellRangeBox(planes, {{0, 0, 0}, {d - 1, d - 1, d - 1}});
      for (int e = 0; e < 60; ++e) {
        std::uniform_real_distribution<double> u(-0.5, 1.5);
        glm::dvec3 eye = all.lo + glm::dvec3(u(rng), u(rng), u(rng)) * all.extent();
        if (e % 5 == 0) eye[e % 3] = planes[size_t(e % 3)][size_t(d / 2)];  // on a plane
        std::vector<int> order = backToFrontRanks(as, planes, eye);
        ASSERT_EQ(order.size(), size_t(P));
        std::vector<int> pos(size_t(P), -1);
        for (int i = 0; i < P; ++i) {
          ASSERT_TRUE(order[size_t(i)] >= 0 && order[size_t(i)] < P &&
                      pos[size_t(order[size_t(i)])] < 0);
          pos[size_t(order[size_t(i)])] = i;
        }
        std::normal_distribution<double> g;
        for (int ray = 0; ray < 300; ++ray) {
          glm::dvec3 dir = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
          std::vector<std::pair<double, int>> hits;
          for (int r = 0; r < P; ++r) {
            double t0, t1;
            if (as.region[size_t(r)].count() == 0 ||
                !intersectRayBox(eye, dir, boxes[size_t(r)], t0, t1))
              continue;
            double entry = std::max(t0, 0.0);
            if (t1 - entry > 1e-9) hits.push_back({entry, r});
          }
          std::sort(hits.begin(), hits.end());
          for (size_t i = 0; i + 1 < hits.size(); ++i)
            if (hits[i + 1].first - hits[i].first > 1e-9)
              ASSERT_LT(pos[size_t(hits[i + 1].second)], pos[size_t(hits[i].second)])
                  << "rank " << hits[i + 1].second << " is farther along a ray than rank "
                  << hits[i].second << " but comes later";
        }
      }
    }
  }
}

TEST(Visibility, SplitTreeLeavesAreTheRegions) {
  for (int d = 1; d <= 4; ++d)
    for (int P = 1; P <= 8; ++P) {
      Assignment as = assignBricks(d, P);
      ASSERT_FALSE(as.tree.empty());
      EXPECT_EQ(as.tree[0].first_rank, 0);
      EXPECT_EQ(as.tree[0].ranks, P);
      std::vector<int> leaf_of(size_t(P), 0);
      for (const KdNode& n : as.tree) {
        if (n.axis >= 0) {
          const KdNode &lo = as.tree[size_t(n.lower)], &hi = as.tree[size_t(n.upper)];
          EXPECT_EQ(lo.first_rank, n.first_rank);
          EXPECT_EQ(lo.ranks, n.ranks / 2);
          EXPECT_EQ(hi.first_rank, n.first_rank + n.ranks / 2);
          EXPECT_EQ(lo.cells.hi[n.axis] + 1, n.cut);
          EXPECT_EQ(hi.cells.lo[n.axis], n.cut);
          continue;
        }
        for (int r = n.first_rank; r < n.first_rank + n.ranks; ++r) ++leaf_of[size_t(r)];
        const IndexBox& reg = as.region[size_t(n.first_rank)];
        EXPECT_EQ(reg.lo, n.cells.lo);
        EXPECT_EQ(reg.hi, n.cells.hi);
        for (int r = n.first_rank + 1; r < n.first_rank + n.ranks; ++r)
          EXPECT_EQ(as.region[size_t(r)].count(), 0);
      }
      for (int r = 0; r < P; ++r) EXPECT_EQ(leaf_of[size_t(r)], 1) << "rank " << r;
    }
}

}  // namespace
}  // namespace sortlast
