#pragma once
// Back-to-front order of non-overlapping axis-aligned boxes seen from an eye point, for
// decompositions that are not sortlast's own kd-split: in situ, each rank's box is the simulation's
// block (slabs, 2x2x1, uneven splits, ranks with nothing).
//
// Two boxes separated along an axis whose extents overlap (with positive length) on the other two
// axes can hide each other: the one on the eye's side of the separating plane is drawn after the
// other. An eye between the two slabs sees neither through the other, so that pair needs no rule.
// The order is a topological sort of these rules (ties: lower index first). For a Cartesian
// decomposition (any MPI_Dims_create grid, even or not) the rules have no cycle and the order is
// the one the slab order of visibility.h gives; a tiling whose rules form a cycle for some eye is
// refused with an error rather than composited wrongly. Empty boxes (lo > hi on some axis) come first.
#include <vector>

#include "common/box.h"

namespace sortlast {

// Indices of `boxes`, far to near. Throws std::runtime_error if the rules form a cycle.
std::vector<int> backToFrontBoxes(const std::vector<Box3>& boxes, const glm::dvec3& eye);

}  // namespace sortlast
