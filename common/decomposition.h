#pragma once
// Which rank owns which brick. A kd-split of the d^3 brick grid: each rank gets a convex box of
// whole bricks (binary-swap needs convex regions whose visibility order is a kd-tree traversal).
// With more ranks than bricks, the surplus ranks own nothing and only take part in compositing.
#include <vector>

#include "common/box.h"

namespace sortlast {

// One node of the split tree: ranks [first_rank, first_rank + ranks) share `cells`. An inner node
// cuts them along `axis` at cell `cut` (lower child: cells below `cut`, the first ranks / 2
// ranks); a leaf gives all of `cells` to first_rank and nothing to the others.
struct KdNode {
  int first_rank = 0, ranks = 1;
  IndexBox cells;
  int axis = -1;               // -1: a leaf
  int cut = 0;                 // first cell of the upper child along `axis`
  int lower = -1, upper = -1;  // children (indices into Assignment::tree)
};

struct Assignment {
  std::vector<int> owner;        // owner[brick id] = rank
  std::vector<IndexBox> region;  // region[rank]: inclusive box of brick cells (empty: count 0)
  std::vector<KdNode> tree;      // the split that made the regions; tree[0] is the root
  std::vector<int> bricksOf(int rank) const;
};

Assignment assignBricks(int d, int ranks);

}  // namespace sortlast
