// Visibility order of arbitrary block decompositions (compositing/box_order.h): on Cartesian grids
// it must agree with the slab order of visibility.h; ranks with nothing come first; an eye between
// slabs needs no rule; and every pair that a ray can cross in both orders is ordered correctly.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "compositing/box_order.h"
#include "common/visibility.h"

namespace sortlast {
namespace {

// A ray from the eye through a point of box b that first passes through box a: a must come later.
// Checked by sampling segments eye -> point in b and testing whether they cross a before.
bool mustBeAfter(const Box3& a, const Box3& b, const glm::dvec3& eye, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    glm::dvec3 p = b.lo + (b.hi - b.lo) * glm::dvec3(u(rng), u(rng), u(rng));
    double t0, t1;
    if (intersectRayBox(eye, p - eye, a, t0, t1) && std::min(t1, 1.0) - std::max(t0, 0.0) > 1e-9) return true;
  }
  return false;
}

std::vector<Box3> grid(const std::vector<double>& xs, const std::vector<double>& ys, const std::vector<double>& zs) {
  std::vector<Box3> boxes;
  for (size_t k = 0; k + 1 < zs.size(); ++k)
    for (size_t j = 0; j + 1 < ys.size(); ++j)
      for (size_t i = 0; i + 1 < xs.size(); ++i)
        boxes.push_back({{xs[i], ys[j], zs[k]}, {xs[i + 1], ys[j + 1], zs[k + 1]}});
  return boxes;
}

TEST(BoxOrder, MatchesSlabOrderOnCartesianGrids) {
  std::array<std::vector<double>, 3> planes = {std::vector<double>{0, 1, 3, 4}, std::vector<double>{0, 2, 3},
                                               std::vector<double>{-1, 0, 0.5, 2}};
  std::vector<Box3> boxes = grid(planes[0], planes[1], planes[2]);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-6.0, 8.0);
  for (int t = 0; t < 200; ++t) {
    glm::dvec3 eye(u(rng), u(rng), u(rng));
    if (Box3{{0, 0, -1}, {4, 3, 2}}.contains(eye)) continue;  // cameras stay outside the data
    std::vector<int> order = backToFrontBoxes(boxes, eye);
    // Every pair a ray crosses in sequence is ordered far to near.
    std::vector<int> pos(boxes.size());
    for (size_t i = 0; i < order.size(); ++i) pos[size_t(order[i])] = int(i);
    for (size_t a = 0; a < boxes.size(); ++a)
      for (size_t b = 0; b < boxes.size(); ++b)
        if (a != b && mustBeAfter(boxes[a], boxes[b], eye, rng))
          EXPECT_GT(pos[a], pos[b]) << "eye " << eye.x << "," << eye.y << "," << eye.z << " boxes " << a << " " << b;
  }
}

TEST(BoxOrder, EmptyBoxesFirstAndUnevenSlabs) {
  std::vector<Box3> boxes = {{{0, 0, 0}, {1, 1, 5}}, {{1, 0, 0}, {-1, -1, -1}} /* empty */, {{1, 0, 0}, {4, 1, 5}},
                             {{4, 0, 0}, {4.5, 1, 5}}};
  std::vector<int> order = backToFrontBoxes(boxes, {10, 0.5, 2});
  ASSERT_EQ(order.size(), 4u);
  EXPECT_EQ(order[0], 1);
  EXPECT_EQ((std::vector<int>{order[1], order[2], order[3]}), (std::vector<int>{0, 2, 3}));
  order = backToFrontBoxes(boxes, {-10, 0.5, 2});
  EXPECT_EQ((std::vector<int>{order[1], order[2], order[3]}), (std::vector<int>{3, 2, 0}));
}

TEST(BoxOrder, StaggeredBricksAreOrdered) {
  // Two layers whose x cuts differ (not a Cartesian grid): still ordered by the pairwise rules.
  std::vector<Box3> boxes = {{{0, 0, 0}, {1, 1, 1}}, {{1, 0, 0}, {3, 1, 1}},
                             {{0, 1, 0}, {2, 2, 1}}, {{2, 1, 0}, {3, 2, 1}}};
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-4.0, 7.0);
  for (int t = 0; t < 100; ++t) {
    glm::dvec3 eye(u(rng), u(rng), u(rng) + 3.0);
    std::vector<int> order = backToFrontBoxes(boxes, eye);
    std::vector<int> pos(boxes.size());
    for (size_t i = 0; i < order.size(); ++i) pos[size_t(order[i])] = int(i);
    for (size_t a = 0; a < boxes.size(); ++a)
      for (size_t b = 0; b < boxes.size(); ++b)
        if (a != b && mustBeAfter(boxes[a], boxes[b], eye, rng)) EXPECT_GT(pos[a], pos[b]);
  }
}

}  // namespace
}  // namespace sortlast
