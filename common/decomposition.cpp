#include "common/decomposition.h"

#include <algorithm>
#include <cmath>

namespace sortlast {

namespace {

// Splits `cells` among ranks [first_rank, first_rank + n_ranks); returns the index of its node.
int split(const IndexBox& cells, int first_rank, int n_ranks, int d, Assignment& out) {
  const int node = int(out.tree.size());
  out.tree.push_back({first_rank, n_ranks, cells});
  glm::ivec3 size = cells.size();
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (size[a] > size[axis]) axis = a;
  if (n_ranks == 1 || size[axis] == 1) {
    // One rank takes the whole box (the others in [first_rank, first_rank + n_ranks) get nothing).
    out.region[first_rank] = cells;
    for (int z = cells.lo.z; z <= cells.hi.z; ++z)
      for (int y = cells.lo.y; y <= cells.hi.y; ++y)
        for (int x = cells.lo.x; x <= cells.hi.x; ++x) out.owner[x + d * (y + d * z)] = first_rank;
    return node;
  }
  int left_ranks = n_ranks / 2;
  int cut =
      std::clamp(int(std::lround(double(size[axis]) * left_ranks / n_ranks)), 1, size[axis] - 1);
  IndexBox left = cells, right = cells;
  left.hi[axis] = cells.lo[axis] + cut - 1;
  right.lo[axis] = cells.lo[axis] + cut;
  int lower = split(left, first_rank, left_ranks, d, out);
  int upper = split(right, first_rank + left_ranks, n_ranks - left_ranks, d, out);
  KdNode& n = out.tree[size_t(node)];
  n.axis = axis;
  n.cut = right.lo[axis];
  n.lower = lower;
  n.upper = upper;
  return node;
}

}  // namespace

std::vector<int> Assignment::bricksOf(int rank) const {
  std::vector<int> ids;
  for (int i = 0; i < int(owner.size()); ++i)
    if (owner[i] == rank) ids.push_back(i);
  return ids;
}

Assignment assignBricks(int d, int ranks) {
  Assignment a;
  a.owner.assign(size_t(d) * d * d, -1);
  a.region.assign(size_t(ranks), IndexBox{});
  split(IndexBox{{0, 0, 0}, {d - 1, d - 1, d - 1}}, 0, ranks, d, a);
  return a;
}

}  // namespace sortlast
