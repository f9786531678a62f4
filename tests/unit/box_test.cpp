// Box algebra (common/box.h): the closed view (isEmpty) and the half-open one (hasVolume) differ
// exactly where two boxes only touch, which callers rely on: a surface touching a brick's face is
// the brick's (BrickRenderer::addHandles), a glow share of zero thickness is not
// (RenderSession's brick shares of glow.box).
#include <gtest/gtest.h>

#include "common/box.h"

namespace sortlast {
namespace {

TEST(Box, TouchingBoxesShareAFaceThatIsNotEmptyButHasNoVolume) {
  const Box3 a{{0, 0, 0}, {1, 1, 1}}, b{{1, 0.25, -1}, {2, 2, 0.5}};
  const Box3 face = intersect(a, b);
  EXPECT_EQ(face.lo, glm::dvec3(1, 0.25, 0));
  EXPECT_EQ(face.hi, glm::dvec3(1, 1, 0.5));
  EXPECT_FALSE(isEmpty(face));
  EXPECT_FALSE(hasVolume(face));
  EXPECT_TRUE(hasVolume(intersect(a, Box3{{0.5, 0.5, 0.5}, {3, 3, 3}})));
}

TEST(Box, EmptyOnAnyAxis) {
  EXPECT_TRUE(isEmpty(noBox()));
  EXPECT_FALSE(hasVolume(noBox()));
  const Box3 a{{0, 0, 0}, {1, 1, 1}};
  for (int axis = 0; axis < 3; ++axis) {
    Box3 apart = a;
    apart.lo[axis] = 2;  // past a on this axis only
    apart.hi[axis] = 3;
    EXPECT_TRUE(isEmpty(intersect(a, apart))) << "axis " << axis;
  }
}

TEST(Box, UniteAndIntersectAreExact) {
  const Box3 a{{0.1, -0.3, 1e-9}, {0.7, 0.2, 1}}, b{{0.3, -1, 0}, {2, 0.1, 1 + 1e-12}};
  const Box3 u = unite(a, b), i = intersect(a, b);
  EXPECT_EQ(u.lo, glm::dvec3(0.1, -1, 0));
  EXPECT_EQ(u.hi, glm::dvec3(2, 0.2, 1 + 1e-12));
  EXPECT_EQ(i.lo, glm::dvec3(0.3, -0.3, 1e-9));
  EXPECT_EQ(i.hi, glm::dvec3(0.7, 0.1, 1));
}

TEST(Box, IndexBoxesAreInclusive) {
  const IndexBox a{{0, 0, 0}, {4, 4, 4}};
  // One shared layer of samples (x = 4), 3 by 5 of them.
  EXPECT_EQ(intersect(a, IndexBox{{4, 2, 0}, {9, 9, 9}}).count(), 1LL * 1 * 3 * 5);
  EXPECT_EQ(intersect(a, IndexBox{{5, 0, 0}, {9, 4, 4}}).count(), 0);
}

}  // namespace
}  // namespace sortlast
