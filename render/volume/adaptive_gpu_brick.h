#pragma once
// An adaptive brick (adaptive/adaptive_brick.h) on the GPU, as the ray caster draws it: the brick's
// atlas as a trilinear GL_R32F 3D texture, its cell table as an RGBA32F 3D texture read with
// texelFetch, and its cells as the ray caster's block grid (planes, world boxes, value ranges),
// so empty-space skipping and the DDA walk the adaptive blocks.
#include <glm/glm.hpp>

#include "adaptive/adaptive_brick.h"
#include "common/brick.h"
#include "common/grid.h"
#include "render/gl/gl_api.h"
#include "render/volume/volume_brick.h"

namespace sortlast {

struct AdaptiveGpuBrick {
  // block_count, block_planes, blocks: the cells; texture: the atlas (texture unit 0). tex_scale
  // and tex_offset are unused: the shader finds texels through the table.
  VolumeBrick volume;
  unsigned table = 0;  // RGBA32F, one texel per cell: atlas offset x, y, z and 2^-level
  // Sample index relative to the origin of cell (0, 0, 0)'s block = world * scale + offset.
  glm::vec3 index_scale{1.0f}, index_offset{0.0f};
  glm::vec3 block_cells{1.0f};  // s per axis
  glm::vec3 atlas_inv{1.0f};    // 1 / atlas dims
};

// Uploads the atlas to texture unit 0 and the table to unit 5; the owner deletes both textures.
AdaptiveGpuBrick uploadAdaptiveBrick(const GlApi& gl, const Brick& brick, const GridGeometry& grid,
                                     const AdaptiveBrickBlocks& blocks);

}  // namespace sortlast
