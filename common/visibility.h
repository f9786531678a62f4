#pragma once
// Back-to-front order of the bricks of a rectilinear grid, seen from an eye point. Exact under
// perspective: along each axis the slabs are ordered far to near (the slab holding the eye last),
// and the axes are nested like the levels of a kd-tree, so no brick is drawn after one that hides
// it. The same rule orders the convex rank regions of a kd-split.
#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "common/box.h"
#include "common/brick_planes.h"
#include "common/camera.h"
#include "common/decomposition.h"

namespace sortlast {

// planes[a] holds the d + 1 slab boundaries along axis a (increasing). Returns the cell indices
// (x + d * (y + d * z)) far to near.
std::vector<int> backToFrontOrder(const std::array<std::vector<double>, 3>& planes,
                                  const glm::dvec3& eye);

// Slab order along one axis, far to near.
std::vector<int> slabOrder(const std::vector<double>& planes, double eye);

// Every rank far to near: a traversal of the assignment's split tree that visits, at each cut,
// the side away from the eye first. Ranks that own nothing come first (they hide nothing).
std::vector<int> backToFrontRanks(const Assignment& assignment, const BrickPlanes& planes,
                                  const glm::dvec3& eye);

// The point the orders above are taken from for `cam`: its eye under perspective (an eye inside
// the bricks sees its own slab, and its own rank's region, last). Orthographic rays are parallel:
// the eye at infinity along -forward(). On each axis the view direction climbs, that is a
// coordinate below every plane of `bounds` (above, where it falls; the eye's own coordinate where
// the rays never cross the axis's planes), so every slab is ordered by the view direction alone.
glm::dvec3 orderEye(const Camera& cam, const Box3& bounds);

// What a compositor needs to know of one frame's visibility.
struct VisibilityOrder {
  std::vector<int> bricks;  // every brick id, far to near
  std::vector<int> ranks;   // every rank, far to near (each rank's region is convex)
};
VisibilityOrder visibilityOrder(const Assignment& assignment, const BrickPlanes& planes,
                                const glm::dvec3& eye);

}  // namespace sortlast
