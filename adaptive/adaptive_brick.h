#pragma once
// The part of an adaptive volume (adaptive/adaptive_blocks.h) that one brick draws: the blocks its
// domain overlaps, packed into an atlas of their own, and the cells the ray caster walks. Plain
// data: render/volume/adaptive_gpu_brick.h uploads it; sampleCell() is the shader's lookup on the CPU,
// so the GPU contract is tested without GL.
//
// Cells. The brick's domain cut at every block plane that crosses it: cell (i, j, k) is the part
// of block `first + (i, j, k)` inside the brick, so every cell has one level. Its planes are the
// brick's faces and the block planes between them (sample indices); a face shared with the
// neighbouring brick is the same index there, so both bricks compute the same float for it.
//
// Whole blocks. A block cut by a brick face is held whole by every brick it overlaps, samples
// beyond the face included: every brick reads the same field in it, and the ray caster's coarse
// samples, which may sit up to 2^level - 1 lattice steps before a cell's entry (beyond the brick's
// face), read the block's own data in every brick (render/volume/raycast_march.frag.glsl).
#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "adaptive/adaptive_blocks.h"
#include "common/box.h"

namespace sortlast {

struct AdaptiveBrickBlocks {
  glm::ivec3 block_cells{1};               // s: cells per block per axis (the volume's)
  glm::ivec3 first{0};                     // block-grid cell of cell (0, 0, 0)
  glm::ivec3 count{0};                     // cells per axis
  std::array<std::vector<int>, 3> planes;  // per axis, count + 1 sample indices: the cells' planes
  // Per cell, x fastest: the block's level, its offset in `atlas`, and the range of all its
  // samples (the whole block's, not only the brick's part: a conservative emptiness test).
  std::vector<AdaptiveBlock> table;
  glm::ivec3 atlas_dims{0};
  std::vector<float> atlas;  // atlas_dims samples, x fastest

  int cellId(const glm::ivec3& c) const { return c.x + count.x * (c.y + count.y * c.z); }
  // Per cell, as AdaptiveVolume::tableTexels: atlas offset x, y, z and 2^-level.
  std::vector<float> tableTexels() const { return sortlast::tableTexels(table); }
};

// The blocks of `vol` that the brick spanning the sample box `domain` (at least one cell per axis)
// draws, their samples copied out of the volume's atlas.
AdaptiveBrickBlocks adaptiveBrickBlocks(const AdaptiveVolume& vol, const IndexBox& domain);

// The shader's lookup: the field at `index` (the volume's sample index space) read from cell
// `cell`'s block, the block-local coordinate clamped to the block's closed box. Inside that box
// this is sampleIndex() of the whole volume (bit for bit where the point lies in no other block's
// box; on a shared face the two blocks agree up to the float rounding of stitched samples);
// outside it, the block's value at the nearest point of the box.
double sampleCell(const AdaptiveBrickBlocks& b, const glm::ivec3& cell, const glm::dvec3& index);

}  // namespace sortlast
