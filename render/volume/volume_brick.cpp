#include "render/volume/volume_brick.h"

#include "io/volume_source.h"  // widenRange

#include <stdexcept>

namespace sortlast {

// Missing samples (NaN: io/volume_source.h) are left out; a box of only missing samples has
// vmin > vmax, which no transfer function sees (TransferFunction::tableSpanVisible).
std::pair<float, float> FloatBrickSamples::range(const IndexBox& box) const {
  const glm::ivec3 n = stored_.size();
  float vmin = 1e30f, vmax = -1e30f;
  for (int z = box.lo.z; z <= box.hi.z; ++z)
    for (int y = box.lo.y; y <= box.hi.y; ++y) {
      const float* row = &samples_[size_t(box.lo.x - stored_.lo.x) +
                                   size_t(n.x) * (size_t(y - stored_.lo.y) + size_t(n.y) * (z - stored_.lo.z))];
      widenRange(row, size_t(box.hi.x - box.lo.x + 1), vmin, vmax);
    }
  return {vmin, vmax};
}

void FloatBrickSamples::upload(const GlApi& gl, const IndexBox& stored) const {
  const glm::ivec3 n = stored.size();
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, n.x, n.y, n.z, GL_RED, GL_FLOAT, samples_.data());
}

VolumeBrick uploadVolumeBrick(const GlApi& gl, const Brick& brick, const GridGeometry& grid,
                              const std::vector<float>& samples, int block_cells) {
  if (samples.size() != size_t(brick.stored.count()))
    throw std::logic_error("addBrick: sample count does not match the brick");
  return uploadVolumeBrick(gl, brick, grid, FloatBrickSamples(samples, brick.stored), block_cells);
}

VolumeBrick uploadVolumeBrick(const GlApi& gl, const Brick& brick, const GridGeometry& grid,
                              const BrickSamples& samples, int block_cells, VolumeTexturePool* pool) {
  VolumeBrick g;
  g.brick = brick;
  g.spacing = grid.spacing;
  glm::ivec3 n = brick.stored.size();
  // Block grid over the brick's cells; each block keeps the range of the samples it spans. None
  // for block_cells 0 (the ray caster: its blocks are its own), which spares two scans of the
  // samples (in situ, of the simulation's array).
  glm::ivec3 cells = brick.domain.size() - 1,
             nb = block_cells > 0 ? (cells + block_cells - 1) / block_cells : glm::ivec3(0);
  g.block_count = nb;
  std::array<std::vector<int>, 3> cuts;
  for (int a = 0; a < 3 && block_cells > 0; ++a) {
    for (int i = 0; i <= nb[a]; ++i)
      cuts[a].push_back(brick.domain.lo[a] + int((long long)cells[a] * i / nb[a]));
    for (int c : cuts[a]) {
      glm::dvec3 idx(0.0);
      idx[a] = c;
      g.block_planes[a].push_back(grid.worldOfIndex(idx)[a]);
    }
  }
  for (int bz = 0; bz < nb.z; ++bz)
    for (int by = 0; by < nb.y; ++by)
      for (int bx = 0; bx < nb.x; ++bx) {
        IndexBox box{{cuts[0][bx], cuts[1][by], cuts[2][bz]},
                     {cuts[0][bx + 1], cuts[1][by + 1], cuts[2][bz + 1]}};
        auto [vmin, vmax] = samples.range(box);
        const IndexBox grown = intersect(IndexBox{box.lo - 1, box.hi + 1}, brick.stored);
        auto [gmin, gmax] = samples.range(grown);
        g.blocks.push_back(VolumeBlock{grid.worldBoxOf(box), vmin, vmax, gmin, gmax});
      }
  // Texel centres: stored sample s sits at texture coordinate (s - stored.lo + 0.5) / n, and the
  // sample index of world point p is p / spacing + (dims - 1) / 2.
  glm::dvec3 inv_n = 1.0 / glm::dvec3(n);
  g.tex_scale = glm::vec3(inv_n / grid.spacing);
  g.tex_offset =
      glm::vec3((0.5 * glm::dvec3(grid.dims - 1) - glm::dvec3(brick.stored.lo) + 0.5) * inv_n);
  g.index_scale = 1.0 / grid.spacing;
  g.index_offset = 0.5 * glm::dvec3(grid.dims - 1) - glm::dvec3(brick.stored.lo);
  gl.ActiveTexture(GL_TEXTURE0);
  if (pool) {
    g.texture = pool->take(n);
  } else {
    g.texture = newVolumeTexture(gl, n);
  }
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  samples.upload(gl, brick.stored);  // every texel of the stored box
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum w : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    gl.TexParameteri(GL_TEXTURE_3D, w, GL_CLAMP_TO_EDGE);
  gl.check("brick texture upload");
  return g;
}

}  // namespace sortlast
