#pragma once
// Several fields in one brick (the `volumes` key, scene/fields_scene.h): what the ray caster gets
// of each field for a brick of the scene's layout. The layout cuts one grid covering every field
// (fieldsGrid), and each field hands each brick its own samples inside the brick's box, with one
// ghost sample beyond (its trilinear filter's stencil at any point of the box, float rounding
// included): a texture on the field's own grid, which the ray caster maps world points into.
// A field that does not reach the brick has no part there. Pure CPU: no GL.
#include <array>
#include <vector>

#include "common/box.h"
#include "common/grid.h"
#include "transfer/transfer_function.h"

namespace sortlast {

struct FieldBrickPart {
  int field = 0;                          // which field (the scene's order)
  GridGeometry grid;                      // the field's
  IndexBox stored;                        // its samples held, on its grid
  const std::vector<float>* samples = nullptr;  // stored.count() values, x fastest
};

// The samples of a field's grid that a world box needs: every sample of the trilinear stencil of
// every point of the box, plus one on each side, clamped to the grid. `present` false: the box
// does not meet the field's box (then the box returned is meaningless).
IndexBox fieldBoxOf(const GridGeometry& field, const Box3& world, bool& present);

// Per block of a brick (the block planes, world positions per axis, count + 1 each; x fastest),
// the range of a field part's samples over the block's stencil: every value the field takes in
// the block. A block the field does not reach gets vmin > vmax (no transfer function sees it).
void fieldBlockRanges(const FieldBrickPart& part, const std::array<std::vector<double>, 3>& planes,
                      std::vector<float>& vmin, std::vector<float>& vmax);

}  // namespace sortlast
