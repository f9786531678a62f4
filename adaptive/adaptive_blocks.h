#pragma once
// Adaptive sampling (the paper's section 4.2): the volume is cut into blocks, and each block is
// stored at the coarsest of its resolutions whose error against the original stays within a
// tolerance. This header is the CPU side of it: the block grid, the preprocessing, the packed
// result (an atlas of every block's samples plus a per-block table, ready to upload as textures)
// and the sampler that defines the field the renderers must reproduce. No GL, no MPI.
//
// Layout. The grid is vertex-centred (common/grid.h): N samples span N - 1 cells per axis. The
// block grid cuts the cells of the whole volume (not of a brick) into blocks of s = 2^k cells per
// axis, s the smallest power of two with b * s >= N - 1, so there are ceil((N - 1) / s) <= b
// blocks per axis. The last block may reach past the last sample; that padding is filled by
// repeating the last sample and is never sampled (the field ends at N - 1). A block at level l
// stores s / 2^l + 1 samples per axis, spaced 2^l cells apart, INCLUDING both faces: every block
// interpolates inside itself only (trilinear, exactly like the full-resolution field), and a GPU
// block never needs its neighbour's texels.
//
// Levels. Level l of the whole volume is built from level l - 1 with the vertex-centred form of
// the paper's "mean of 2 x 2 x 2": a coarse sample is the mean of the 2 x 2 x 2 fine cells around
// it, each cell taken as the mean of its corners; per axis that is the weights (1/4, 1/2, 1/4)
// (mirrored at the ends). The pyramid is global, so blocks at the same level agree on the samples
// of their shared face without any fix-up.
//
// Tolerance. For each block, in order l = 1, 2, ..., the squared error of eq. 3, taken against the
// original at every original sample of the block's closed box (faces included),
//     E_l = sum (v_0(i,j,k) - r_l(i,j,k))^2    (r_l: the block's level-l samples, trilinear)
// must stay within  tolerance^2 * sum v_0(i,j,k)^2  over the same samples; the block takes the
// last level before the first one that exceeds it. So "10 %" is a relative L2 error: the block's
// RMS error is at most 10 % of its RMS value. The paper gives eq. 3 and percentages but not what
// the percentage is of; the relative L2 error is the usual meaning of "x % error", is free of the
// data's scale, and tolerance 0 keeps a block coarse only where that loses nothing (the field then
// equals the original at every sample). results/adaptive/README.md compares the alternatives.
// The test is on each block's own samples; the stitching below can move a block's face samples,
// and with them its error, so a few blocks end over their tolerance (AdaptiveSummary counts them).
//
// No cracks. Where neighbours differ in level, the finer block's face samples are replaced by the
// coarser neighbour's field on that face (bilinear between its samples), and likewise on edges
// and corners, where the coarsest of the 4 (or 8) blocks that share them decides. A piecewise-
// bilinear function on a coarse lattice is reproduced exactly by bilinear interpolation of its
// values on any finer nested lattice, so both sides of every block face carry the same function:
// the field is continuous everywhere (up to float rounding of the stored samples). Because the
// block grid and the levels belong to the whole volume, two bricks rendered by different ranks see
// the same field on their shared face, whether or not brick faces fall on block faces.
#include <glm/glm.hpp>
#include <utility>
#include <vector>

#include "common/box.h"
#include "common/grid.h"

namespace sortlast {

// The block grid of a volume: geometry only.
struct BlockGrid {
  glm::ivec3 dims{0};         // samples of the volume per axis
  glm::ivec3 block_cells{1};  // s: cells per block per axis (a power of two)
  glm::ivec3 blocks{0};       // blocks per axis: ceil((dims - 1) / s)
  int max_level = 0;          // log2(smallest s): level l has s / 2^l >= 1 cells per axis

  int count() const { return blocks.x * blocks.y * blocks.z; }
  int id(const glm::ivec3& c) const { return c.x + blocks.x * (c.y + blocks.y * c.z); }
  glm::ivec3 cellOf(int id) const {
    return {id % blocks.x, (id / blocks.x) % blocks.y, id / (blocks.x * blocks.y)};
  }
  // Samples (index space, closed) of block c; may reach past dims - 1 in the last block.
  IndexBox samplesOf(const glm::ivec3& c) const { return {c * block_cells, (c + 1) * block_cells}; }
  // Samples per axis a block stores at `level`.
  glm::ivec3 samplesAt(int level) const { return (block_cells >> level) + 1; }
};

// b: blocks per axis asked for (a power of two in [1, 256]). Throws InputError naming
// adaptive.blocks otherwise.
BlockGrid makeBlockGrid(const glm::ivec3& dims, int b);

// Ids of the blocks whose cells overlap the sample box (e.g. a brick's domain): the blocks a
// brick has to draw, clipped to its box.
std::vector<int> blocksOverlapping(const BlockGrid& grid, const IndexBox& samples);

struct AdaptiveBlock {
  int level = 0;               // 0: full resolution; each level halves the samples per axis
  glm::ivec3 atlas_offset{0};  // texel of the block's first sample in the atlas
  float vmin = 0, vmax = 0;    // range of its stored samples = range of the field in the block
};

// Per block of `table` 4 floats: atlas offset x, y, z and 2^-level (an RGBA32F texel).
std::vector<float> tableTexels(const std::vector<AdaptiveBlock>& table);

struct AdaptiveTimings {
  double pyramid_s = 0, levels_s = 0, pack_s = 0;
  double total() const { return pyramid_s + levels_s + pack_s; }
};

// The packed result: one atlas holding every block's samples at its level, and the table.
struct AdaptiveVolume {
  GridGeometry grid;
  BlockGrid blocks;
  double tolerance = 0;              // relative L2 error per block, a fraction (0.1 = 10 %)
  std::vector<AdaptiveBlock> table;  // per block id
  glm::ivec3 atlas_dims{0};
  std::vector<float> atlas;  // atlas_dims samples, x fastest; unused texels hold 0
  AdaptiveTimings timings;

  // Per block (id order) 4 floats: atlas offset x, y, z and 2^-level, i.e. an RGBA32F texture of
  // blocks.blocks texels that a shader reads with texelFetch(table, cell).
  std::vector<float> tableTexels() const { return sortlast::tableTexels(table); }
  long long atlasTexels() const { return (long long)atlas_dims.x * atlas_dims.y * atlas_dims.z; }
};

struct AdaptiveOptions {
  int blocks_per_axis = 8;  // b
  double tolerance = 0.0;   // relative L2 error per block, a fraction (0.1 = 10 %), >= 0
  int threads = 0;          // 0: all cores
};

// Builds the representation of a whole volume (samples x fastest, grid.dims of them). Throws
// InputError for a bad b or tolerance (naming adaptive.blocks / adaptive.tolerance) and for a
// sample count that does not match the grid.
AdaptiveVolume buildAdaptive(const GridGeometry& grid, const std::vector<float>& samples,
                             const AdaptiveOptions& options);

// The same, keeping its memory from one call to the next: build every time step of a series with
// one builder. Fresh memory is dear here: first-touching a new 80 MB atlas (256^3, tolerance 0)
// took 0.24 s on the project's machine, more than all the preprocessing with warm buffers.
class AdaptiveBuilder {
 public:
  // The result stays valid (and owned by the builder) until the next build().
  const AdaptiveVolume& build(const GridGeometry& grid, const std::vector<float>& samples,
                              const AdaptiveOptions& options);
  AdaptiveVolume take() { return std::move(out_); }

 private:
  AdaptiveVolume out_;
  std::vector<std::vector<float>> pyramid_;  // levels 1.. of the last volume
};

// The adaptive field at a point in index space (sample (i,j,k) at (i,j,k)), clamped to the
// volume. This is the exact field a GPU sampler must reproduce:
//   c     = min(floor(u / s), blocks - 1)            the block (per axis)
//   local = (u - c * s) * 2^-level                   lattice coordinate in the block, [0, s/2^l]
//   i     = min(floor(local), s/2^l - 1), f = local - i
//   value = trilinear(atlas, atlas_offset + i, f)    x first, then y, then z
// With GL_LINEAR filtering the same is texture(atlas, (atlas_offset + local + 0.5) / atlas_dims)
// (a texel outside the block's own is touched only with weight 0, at its upper faces), up to the
// precision of the hardware's filter weights (8 fractional bits on NVIDIA): for the exact field,
// fetch the 8 texels and interpolate in the shader.
double sampleIndex(const AdaptiveVolume& vol, const glm::dvec3& index);
// The same at a world position (common/grid.h).
inline double sample(const AdaptiveVolume& vol, const glm::dvec3& world) {
  return sampleIndex(vol, vol.grid.indexOfWorld(world));
}

// Places the blocks of `table` (any subset of a grid's blocks, each with its level) in an atlas:
// sets each atlas_offset and returns the atlas dims. buildAdaptive packs the whole volume with it;
// a brick packs the blocks it draws (adaptive/adaptive_brick.h).
glm::ivec3 packAtlas(const BlockGrid& grid, std::vector<AdaptiveBlock>& table);

// AdaptiveSummary::data_left alone (no pass over the samples): cheap enough for every render.
double dataLeft(const AdaptiveVolume& vol);

// How much the representation keeps and what it costs in accuracy.
struct AdaptiveSummary {
  // The paper's measure: the samples the blocks hold at their levels, counting each block's
  // shared face samples once (s / 2^l per axis), as a fraction of what the same blocks hold at
  // full resolution (s per axis; for 2^k samples per axis that is the original sample count).
  double data_left = 0;
  // What the atlas really holds per block ((s / 2^l + 1)^3, faces duplicated), as a fraction of
  // the original sample count: the memory against the original volume's.
  double stored_fraction = 0;
  std::vector<int> blocks_per_level;  // index = level
  // The adaptive field at every original sample against the original.
  double max_error = 0, rms_error = 0;
  // The tolerance holds for each block's own choice of level; stitching then gives a finer
  // block's face samples its coarser neighbours' values, which can push its error past it. How
  // many blocks end over their tolerance (eq. 3 of the final field > tolerance^2 sum v^2 over the
  // closed box), and the largest relative L2 error of a block (sqrt(eq. 3 / sum v^2); infinite for
  // an all-zero block with any error).
  int blocks_over_tolerance = 0;
  double worst_block_relative_error = 0;
};
AdaptiveSummary summarise(const AdaptiveVolume& vol, const std::vector<float>& original,
                          int threads = 0);

}  // namespace sortlast
