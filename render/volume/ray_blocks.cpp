#include "render/volume/ray_blocks.h"

#include <algorithm>
#include <tuple>

namespace sortlast {

RayBlockGrid rayBlockGrid(const GridGeometry& grid, int cells) {
  RayBlockGrid g;
  g.cells = std::max(1, cells);
  // Blocks far larger than the volume (render.ray_block_cells: 100000, one block per brick) must
  // not overflow the arithmetic below.
  g.cells = std::min(g.cells, 1 << 20);
  g.count = glm::max((grid.dims - 1 + g.cells - 1) / g.cells, glm::ivec3(1));
  return g;
}

BrickBlocks cutBrickBlocks(const Brick& brick, const GridGeometry& grid, const BrickSamples& samples,
                           const RayBlockGrid& blocks) {
  BrickBlocks b;
  const int B = blocks.cells;
  std::array<std::vector<int>, 3> cuts;
  for (int a = 0; a < 3; ++a) {
    const int lo = brick.domain.lo[a], hi = brick.domain.hi[a];
    b.first[a] = lo / B;
    cuts[a].push_back(lo);
    for (int c = (lo / B + 1) * B; c < hi; c += B) cuts[a].push_back(c);
    cuts[a].push_back(hi);
    b.count[a] = int(cuts[a].size()) - 1;
    for (int c : cuts[a]) {
      glm::dvec3 idx(0.0);
      idx[a] = c;
      // The same double, hence float, for a plane in every brick that has it.
      b.planes[a].push_back(grid.worldOfIndex(idx)[a]);
    }
  }
  const size_t n = size_t(b.count.x) * size_t(b.count.y) * size_t(b.count.z);
  b.vmin.resize(n);
  b.vmax.resize(n);
  b.grown_min.resize(n);
  b.grown_max.resize(n);
  for (int z = 0; z < b.count.z; ++z)
    for (int y = 0; y < b.count.y; ++y)
      for (int x = 0; x < b.count.x; ++x) {
        const size_t i = b.index({x, y, z});
        IndexBox cut{{cuts[0][x], cuts[1][y], cuts[2][z]}, {cuts[0][x + 1], cuts[1][y + 1], cuts[2][z + 1]}};
        std::tie(b.vmin[i], b.vmax[i]) = samples.range(cut);
        const glm::ivec3 c = b.first + glm::ivec3(x, y, z);
        const IndexBox grown = intersect(IndexBox{c * B - 1, (c + 1) * B + 1}, brick.stored);
        std::tie(b.grown_min[i], b.grown_max[i]) = samples.range(grown);
      }
  return b;
}

void mergeGrownRanges(const BrickBlocks& b, const RayBlockGrid& grid, std::vector<float>& vmin,
                      std::vector<float>& vmax) {
  for (int z = 0; z < b.count.z; ++z)
    for (int y = 0; y < b.count.y; ++y)
      for (int x = 0; x < b.count.x; ++x) {
        const glm::ivec3 c = b.first + glm::ivec3(x, y, z);
        const size_t g = size_t(c.x) + size_t(grid.count.x) * (size_t(c.y) + size_t(grid.count.y) * c.z);
        const size_t i = b.index({x, y, z});
        vmin[g] = std::min(vmin[g], b.grown_min[i]);
        vmax[g] = std::max(vmax[g], b.grown_max[i]);
      }
}

std::vector<unsigned char> chessboardDistance(const glm::ivec3& count,
                                              const std::vector<unsigned char>& visible) {
  // Two raster passes over the 26 neighbours (forward: those before a block in x-fastest order,
  // backward: those after), each d = min(d, d(neighbour) + 1): exact for the chessboard metric.
  const int far = 255;
  std::vector<int> d(visible.size());
  for (size_t i = 0; i < d.size(); ++i) d[i] = visible[i] ? 0 : far;
  auto at = [&](int x, int y, int z) -> int& {
    return d[size_t(x) + size_t(count.x) * (size_t(y) + size_t(count.y) * z)];
  };
  auto relax = [&](int x, int y, int z, bool forward) {
    int& v = at(x, y, z);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int order = dz * 9 + dy * 3 + dx;  // < 0: before in x-fastest order
          if (order == 0 || (order < 0) != forward) continue;
          const int nx = x + dx, ny = y + dy, nz = z + dz;
          if (nx < 0 || ny < 0 || nz < 0 || nx >= count.x || ny >= count.y || nz >= count.z) continue;
          v = std::min(v, at(nx, ny, nz) + 1);
        }
  };
  for (int z = 0; z < count.z; ++z)
    for (int y = 0; y < count.y; ++y)
      for (int x = 0; x < count.x; ++x) relax(x, y, z, true);
  for (int z = count.z - 1; z >= 0; --z)
    for (int y = count.y - 1; y >= 0; --y)
      for (int x = count.x - 1; x >= 0; --x) relax(x, y, z, false);
  std::vector<unsigned char> out(d.size());
  for (size_t i = 0; i < d.size(); ++i) out[i] = (unsigned char)std::min(d[i], far);
  return out;
}

std::vector<unsigned char> classReach(const glm::ivec3& count, const std::vector<unsigned char>& cls) {
  std::vector<unsigned char> reach(cls.size(), 255), other(cls.size());
  std::vector<bool> seen(256, false);
  for (unsigned char c : cls) seen[c] = true;
  for (int c = 0; c < 256; ++c) {
    if (!seen[size_t(c)]) continue;
    for (size_t i = 0; i < cls.size(); ++i) other[i] = cls[i] != c;
    const std::vector<unsigned char> d = chessboardDistance(count, other);
    for (size_t i = 0; i < cls.size(); ++i)
      if (cls[i] == c) reach[i] = d[i];
  }
  return reach;
}

}  // namespace sortlast
