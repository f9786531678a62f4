#pragma once
// A brick of volume samples on the GPU, as both volume renderers (slicing, ray casting) hold it:
// a 3D texture of its stored samples (ghosts included, trilinear, clamped), the map from world
// to texture coordinates, and its block grid for empty-space skipping, each block with the range
// of the samples it spans (so whether it is visible can be rechecked under any transfer function).
#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "common/brick.h"
#include "common/grid.h"
#include "render/volume/brick_samples.h"
#include "render/gl/gl_api.h"
#include "render/volume/volume_texture_pool.h"

namespace sortlast {

struct VolumeBlock {
  Box3 world;
  float vmin, vmax;
  // The range of the block grown by one sample on every side (within the stored box, so the
  // ghost layer counts): every value a pre-integrated segment owned by the block reads, as long as
  // its ends lie within one voxel of the block (render/volume/raycast_march.frag.glsl).
  float gmin, gmax;
};

struct VolumeBrick {
  Brick brick;
  glm::ivec3 block_count{0};
  std::array<std::vector<double>, 3> block_planes;  // world block boundaries per axis (count + 1)
  std::vector<VolumeBlock> blocks;                  // x fastest over the block grid
  unsigned texture = 0;                             // GL_R32F 3D texture; the owner deletes it
  glm::vec3 tex_scale, tex_offset;                  // texture coordinate = world * scale + offset
  // The same map in double to texel index coordinates (texel centres at integers): index =
  // world * index_scale + index_offset (exact MIP's cell walk, raycast_projection.frag.glsl).
  glm::dvec3 index_scale{1.0}, index_offset{0.0};
  glm::dvec3 spacing{1.0};                          // the grid's (gradients: render/volume/volume_shading.h)
};

// Cuts the brick's cells into blocks of up to `block_cells` cells per axis (as even as the
// integer cells allow; none for block_cells 0) and uploads the samples (stored box, x fastest)
// to texture unit 0.
// Throws std::logic_error if the sample count does not match the brick.
VolumeBrick uploadVolumeBrick(const GlApi& gl, const Brick& brick, const GridGeometry& grid,
                              const std::vector<float>& samples, int block_cells);
// The same from any source of samples (in situ: the simulation's arrays, read where they lie).
// With `pool`, the texture is a spare of the pool's where one of the size is there.
VolumeBrick uploadVolumeBrick(const GlApi& gl, const Brick& brick, const GridGeometry& grid,
                              const BrickSamples& samples, int block_cells,
                              VolumeTexturePool* pool = nullptr);

}  // namespace sortlast
