#include "common/brick.h"

#include <algorithm>

#include "common/error.h"

namespace sortlast {

std::vector<Brick> makeBricks(const GridGeometry& grid, int d) {
  if (d < 1) throw InputError("bricks.per_axis: must be >= 1");
  for (int a = 0; a < 3; ++a)
    if (grid.dims[a] - 1 < d)
      throw InputError("bricks.per_axis: " + std::to_string(d) + " bricks per axis need at least " +
                       std::to_string(d + 1) + " samples per axis; volume.dims has " +
                       std::to_string(grid.dims[a]));
  // Cut the (dims - 1) cells of each axis into d nearly equal runs.
  auto cut = [&](int axis, int b) { return int((long long)(grid.dims[axis] - 1) * b / d); };
  std::vector<Brick> bricks;
  bricks.reserve(size_t(d) * d * d);
  for (int z = 0; z < d; ++z)
    for (int y = 0; y < d; ++y)
      for (int x = 0; x < d; ++x) {
        Brick b;
        b.id = int(bricks.size());
        b.cell = {x, y, z};
        for (int a = 0; a < 3; ++a) {
          b.domain.lo[a] = cut(a, b.cell[a]);
          b.domain.hi[a] = cut(a, b.cell[a] + 1);
          b.stored.lo[a] = std::max(0, b.domain.lo[a] - 1);
          b.stored.hi[a] = std::min(grid.dims[a] - 1, b.domain.hi[a] + 1);
        }
        b.world = grid.worldBoxOf(b.domain);
        bricks.push_back(b);
      }
  return bricks;
}

}  // namespace sortlast
