#include "render/volume/adaptive_gpu_brick.h"

namespace sortlast {

AdaptiveGpuBrick uploadAdaptiveBrick(const GlApi& gl, const Brick& brick, const GridGeometry& grid,
                                     const AdaptiveBrickBlocks& data) {
  AdaptiveGpuBrick g;
  VolumeBrick& v = g.volume;
  v.brick = brick;
  v.block_count = data.count;
  // World planes by the same formula as VolumeBrick's (worldOfIndex of a sample index), so a
  // brick face is the same double, hence the same float, on both sides and in both renderers.
  for (int a = 0; a < 3; ++a)
    for (int idx : data.planes[a]) {
      glm::dvec3 p(0.0);
      p[a] = idx;
      v.block_planes[a].push_back(grid.worldOfIndex(p)[a]);
    }
  for (int z = 0; z < data.count.z; ++z)
    for (int y = 0; y < data.count.y; ++y)
      for (int x = 0; x < data.count.x; ++x) {
        const AdaptiveBlock& b = data.table[size_t(data.cellId({x, y, z}))];
        IndexBox box{{data.planes[0][x], data.planes[1][y], data.planes[2][z]},
                     {data.planes[0][x + 1], data.planes[1][y + 1], data.planes[2][z + 1]}};
        // The grown range only serves pre-integration, which adaptive bricks refuse: the own one.
        v.blocks.push_back({grid.worldBoxOf(box), b.vmin, b.vmax, b.vmin, b.vmax});
      }
  const glm::dvec3 origin = glm::dvec3(data.first * data.block_cells);
  g.index_scale = glm::vec3(1.0 / grid.spacing);
  g.index_offset = glm::vec3(0.5 * glm::dvec3(grid.dims - 1) - origin);
  g.block_cells = glm::vec3(data.block_cells);
  g.atlas_inv = glm::vec3(1.0 / glm::dvec3(data.atlas_dims));

  gl.GenTextures(1, &v.texture);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_3D, v.texture);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexImage3D(GL_TEXTURE_3D, 0, GL_R32F, data.atlas_dims.x, data.atlas_dims.y, data.atlas_dims.z,
                0, GL_RED, GL_FLOAT, data.atlas.data());
  // Trilinear by the hardware: a lookup stays inside its block's texels (a neighbour's texel is
  // touched only with weight 0, at the block's upper faces), as adaptive/adaptive_blocks.h shows.
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum w : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    gl.TexParameteri(GL_TEXTURE_3D, w, GL_CLAMP_TO_EDGE);

  const std::vector<float> texels = data.tableTexels();
  gl.GenTextures(1, &g.table);
  gl.ActiveTexture(GL_TEXTURE5);
  gl.BindTexture(GL_TEXTURE_3D, g.table);
  gl.TexImage3D(GL_TEXTURE_3D, 0, GL_RGBA32F, data.count.x, data.count.y, data.count.z, 0, GL_RGBA,
                GL_FLOAT, texels.data());
  // Read with texelFetch only; without mipmaps a mipmap filter would make it incomplete.
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.check("adaptive brick upload");
  return g;
}

}  // namespace sortlast
