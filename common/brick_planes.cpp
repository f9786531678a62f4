#include "common/brick_planes.h"

#include <algorithm>

namespace sortlast {

BrickPlanes volumeBrickPlanes(const std::vector<Brick>& bricks, int d) {
  BrickPlanes planes;
  for (int a = 0; a < 3; ++a) {
    for (int i = 0; i < d; ++i) {
      glm::ivec3 cell(0);
      cell[a] = i;
      planes[a].push_back(bricks[size_t(cell.x + d * (cell.y + d * cell.z))].world.lo[a]);
    }
    planes[a].push_back(bricks.back().world.hi[a]);
  }
  return planes;
}

BrickPlanes uniformBrickPlanes(const Box3& box, int d) {
  BrickPlanes planes;
  for (int a = 0; a < 3; ++a) {
    for (int i = 0; i < d; ++i) planes[a].push_back(box.lo[a] + (box.hi[a] - box.lo[a]) * i / d);
    planes[a].push_back(box.hi[a]);  // exactly hi, not lo + extent * d / d
  }
  return planes;
}

BrickPlanes coverBox(BrickPlanes planes, const Box3& box) {
  for (int a = 0; a < 3; ++a) {
    planes[a].front() = std::min(planes[a].front(), box.lo[a]);
    planes[a].back() = std::max(planes[a].back(), box.hi[a]);
  }
  return planes;
}

Box3 brickBox(const BrickPlanes& planes, const glm::ivec3& cell) {
  return cellRangeBox(planes, {cell, cell});
}

Box3 cellRangeBox(const BrickPlanes& planes, const IndexBox& cells) {
  if (cells.count() == 0) return {glm::dvec3(1.0), glm::dvec3(-1.0)};
  Box3 b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = planes[a][size_t(cells.lo[a])];
    b.hi[a] = planes[a][size_t(cells.hi[a]) + 1];
  }
  return b;
}

}  // namespace sortlast
