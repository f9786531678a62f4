#pragma once
// Which rank owns which brick. A kd-split of the d^3 brick grid: each rank gets a convex box of
// whole bricks (binary-swap needs convex regions whose visibility order is a kd-tree traversal).
// With more ranks than bricks, the surplus ranks own nothing and only take part in compositing.
#include <vector>

#include "common/box.h"

namespace sortlast {

struct Assignment {
  std::vector<int> owner;           // owner[brick id] = rank
  std::vector<IndexBox> region;     // region[rank]: inclusive box of brick cells (empty: count 0)
  std::vector<int> bricksOf(int rank) const;
};

Assignment assignBricks(int d, int ranks);

}  // namespace sortlast
