#pragma once
// Back-to-front order of the bricks of a rectilinear grid, seen from an eye point. Exact under
// perspective: along each axis the slabs are ordered far to near (the slab holding the eye last),
// and the axes are nested like the levels of a kd-tree, so no brick is drawn after one that hides
// it. The same rule orders the convex rank regions of a kd-split.
#include <array>
#include <vector>

#include <glm/glm.hpp>

namespace sortlast {

// planes[a] holds the d + 1 slab boundaries along axis a (increasing). Returns the cell indices
// (x + d * (y + d * z)) far to near.
std::vector<int> backToFrontOrder(const std::array<std::vector<double>, 3>& planes,
                                  const glm::dvec3& eye);

// Slab order along one axis, far to near.
std::vector<int> slabOrder(const std::vector<double>& planes, double eye);

}  // namespace sortlast
