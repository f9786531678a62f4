#pragma once
// The brick grid as planes: d + 1 increasing positions per axis. Volume bricks take theirs from the
// sample grid; particle bricks use the same planes when there is a volume (so a volume brick and
// the particles inside it make one brick image), with the outer planes moved out to hold every
// particle, or d equal slabs of the particles' domain when there is none. Either way the bricks
// form a rectilinear grid, which is what the visibility order (common/visibility.h) needs.
#include <array>
#include <vector>

#include "common/box.h"
#include "common/brick.h"

namespace sortlast {

using BrickPlanes = std::array<std::vector<double>, 3>;

BrickPlanes volumeBrickPlanes(const std::vector<Brick>& bricks, int d);
BrickPlanes uniformBrickPlanes(const Box3& box, int d);
// The same grid with its outer planes moved out (never in) so that it covers `box`.
BrickPlanes coverBox(BrickPlanes planes, const Box3& box);

Box3 brickBox(const BrickPlanes& planes, const glm::ivec3& cell);
// Box of the inclusive range of cells `cells` (a rank's region); empty range: an empty box.
Box3 cellRangeBox(const BrickPlanes& planes, const IndexBox& cells);

}  // namespace sortlast
