#pragma once
// The ray caster's blocks (render/volume/raycast_march.frag.glsl walks them): the volume's cells
// cut into blocks of B cells per axis on one grid aligned to the volume (block c spans cells [c B,
// (c+1) B)), the same grid in every decomposition; a brick holds the blocks its cells touch, cut by
// its faces.
// Two things are decided per block, on the CPU, whenever the transfer function changes:
//   - whether it is empty (all its values map to zero opacity), and its step multiple m, together
//     its class; kept with the chessboard distance d in blocks to the nearest block of another
//     class in the brick: a ray crosses the whole cube of blocks within d - 1 around it in one step
//     (jumping it if empty, sampling it with one m otherwise);
//   - the step multiple m = 2^j (render.adaptive_step; render/volume/step_rule.h picks it from the block's
//     value range), which must be the same in every brick sharing the block: it is chosen from the
//     range of the whole block (grown by one sample, where its anchors may lie), which no brick
//     holds alone, so the ranks reduce it (globalRanges / setGlobalRanges in RaycastRenderer).
// Pure CPU: no GL, no MPI.
#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "common/brick.h"
#include "common/grid.h"
#include "render/volume/brick_samples.h"

namespace sortlast {

// The volume's block grid.
struct RayBlockGrid {
  int cells = 8;           // B
  glm::ivec3 count{0};     // blocks per axis
  size_t size() const { return size_t(count.x) * size_t(count.y) * size_t(count.z); }
};
RayBlockGrid rayBlockGrid(const GridGeometry& grid, int cells);

// A brick's blocks: global block `first` + (i, j, k), each cut by the brick's faces.
struct BrickBlocks {
  glm::ivec3 first{0}, count{0};
  std::array<std::vector<double>, 3> planes;  // world positions, count + 1 per axis
  // Range of the samples of each (cut) block, x fastest: whether the brick's part is empty.
  std::vector<float> vmin, vmax;
  // Range of the stored samples (ghosts included) inside each whole block grown by one sample: this
  // brick's part of what the global range reduces.
  std::vector<float> grown_min, grown_max;
  bool global = true;  // false: the blocks are another grid's (adaptive bricks), with no global range
  size_t index(const glm::ivec3& b) const { return size_t(b.x) + size_t(count.x) * (size_t(b.y) + size_t(count.y) * b.z); }
};
BrickBlocks cutBrickBlocks(const Brick& brick, const GridGeometry& grid, const BrickSamples& samples,
                           const RayBlockGrid& blocks);

// Merges a brick's grown ranges into global arrays (min into vmin, max into vmax, x fastest over
// the volume's block grid).
void mergeGrownRanges(const BrickBlocks& b, const RayBlockGrid& grid, std::vector<float>& vmin,
                      std::vector<float>& vmax);

// Chessboard distance, in blocks and capped at 255, from each block to the nearest block with
// visible != 0 (0 there); 255 everywhere when there is none.
std::vector<unsigned char> chessboardDistance(const glm::ivec3& count,
                                              const std::vector<unsigned char>& visible);
// For each block, the chessboard distance d (>= 1, capped at 255) to the nearest block of another
// class: every block within d - 1 of it has its class, so a ray can cross that whole cube of blocks
// at once (classes: empty, or the step multiple of a non-empty block).
std::vector<unsigned char> classReach(const glm::ivec3& count, const std::vector<unsigned char>& cls);

}  // namespace sortlast
