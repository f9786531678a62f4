#include "adaptive/adaptive_brick.h"

#include "common/trilinear.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sortlast {

namespace {
size_t linear(const glm::ivec3& p, const glm::ivec3& d) {
  return size_t(p.x) + size_t(d.x) * (size_t(p.y) + size_t(d.y) * size_t(p.z));
}
}  // namespace

AdaptiveBrickBlocks adaptiveBrickBlocks(const AdaptiveVolume& vol, const IndexBox& domain) {
  const BlockGrid& g = vol.blocks;
  if (glm::any(glm::lessThanEqual(domain.hi, domain.lo)))
    throw std::logic_error("adaptiveBrickBlocks: a brick needs at least one cell per axis");
  AdaptiveBrickBlocks b;
  b.block_cells = g.block_cells;
  const std::vector<int> ids = blocksOverlapping(g, domain);  // x fastest over a box of blocks
  b.first = g.cellOf(ids.front());
  b.count = g.cellOf(ids.back()) - b.first + 1;
  for (int a = 0; a < 3; ++a) {
    b.planes[a].push_back(domain.lo[a]);
    for (int c = b.first[a] + 1; c < b.first[a] + b.count[a]; ++c)
      b.planes[a].push_back(c * g.block_cells[a]);
    b.planes[a].push_back(domain.hi[a]);
  }
  b.table.reserve(ids.size());
  for (int id : ids) b.table.push_back(vol.table[size_t(id)]);
  b.atlas_dims = packAtlas(g, b.table);
  b.atlas.assign(size_t(b.atlas_dims.x) * b.atlas_dims.y * b.atlas_dims.z, 0.0f);
  for (size_t i = 0; i < ids.size(); ++i) {
    const glm::ivec3 from = vol.table[size_t(ids[i])].atlas_offset, to = b.table[i].atlas_offset;
    const glm::ivec3 n = g.samplesAt(b.table[i].level);
    for (int z = 0; z < n.z; ++z)
      for (int y = 0; y < n.y; ++y) {
        const float* src = &vol.atlas[linear(from + glm::ivec3(0, y, z), vol.atlas_dims)];
        std::copy(src, src + n.x, &b.atlas[linear(to + glm::ivec3(0, y, z), b.atlas_dims)]);
      }
  }
  return b;
}

double sampleCell(const AdaptiveBrickBlocks& b, const glm::ivec3& cell, const glm::dvec3& index) {
  const AdaptiveBlock& blk = b.table.at(size_t(b.cellId(cell)));
  const glm::ivec3 origin = (b.first + cell) * b.block_cells;
  int i[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    // sampleIndex's arithmetic, with the block given instead of found from the point.
    const int m = b.block_cells[a] >> blk.level;
    const double local = std::clamp(std::ldexp(index[a] - double(origin[a]), -blk.level), 0.0, double(m));
    i[a] = std::min(int(local), m - 1);
    f[a] = local - i[a];
  }
  const glm::ivec3 o = blk.atlas_offset + glm::ivec3(i[0], i[1], i[2]);
  auto s = [&](int dx, int dy, int dz) {
    return double(b.atlas[linear(o + glm::ivec3(dx, dy, dz), b.atlas_dims)]);
  };
  return trilinear(s, f);
}

}  // namespace sortlast
