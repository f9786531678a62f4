#pragma once
// A brick: one of the d x d x d subvolumes of the grid. Neighbouring bricks share their face
// samples; each also stores one ghost layer beyond its faces so interpolation, and the gradients of
// render.shading (differences one voxel beyond a face: render/volume/volume_shading.h), never read
// outside its own texture.
#include <vector>

#include "common/box.h"
#include "common/grid.h"

namespace sortlast {

struct Brick {
  int id = 0;            // cell.x + d * (cell.y + d * cell.z)
  glm::ivec3 cell{0};    // position in the d^3 brick grid
  IndexBox domain;       // samples spanned by the brick; its field is trilinear between them
  IndexBox stored;       // domain grown by one ghost sample where the volume continues
  Box3 world;            // world box of `domain`
};

// The d^3 bricks of a grid, in id order. Throws InputError if a brick would have no cell.
std::vector<Brick> makeBricks(const GridGeometry& grid, int d);

}  // namespace sortlast
