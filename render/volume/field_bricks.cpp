#include "render/volume/field_bricks.h"

#include <cmath>

#include "io/volume_source.h"  // widenRange

namespace sortlast {

IndexBox fieldBoxOf(const GridGeometry& field, const Box3& world, bool& present) {
  const glm::dvec3 lo = field.indexOfWorld(world.lo), hi = field.indexOfWorld(world.hi);
  const glm::dvec3 last = glm::dvec3(field.dims - 1);
  present = glm::all(glm::lessThanEqual(lo, last)) && glm::all(glm::greaterThanEqual(hi, glm::dvec3(0.0)));
  IndexBox b{glm::ivec3(glm::floor(lo)) - 1, glm::ivec3(glm::ceil(hi)) + 1};
  return intersect(b, IndexBox{glm::ivec3(0), field.dims - 1});
}

void fieldBlockRanges(const FieldBrickPart& part, const std::array<std::vector<double>, 3>& planes,
                      std::vector<float>& vmin, std::vector<float>& vmax) {
  const glm::ivec3 count(int(planes[0].size()) - 1, int(planes[1].size()) - 1, int(planes[2].size()) - 1);
  const glm::ivec3 n = part.stored.size();
  vmin.assign(size_t(count.x) * count.y * count.z, 1e30f);
  vmax.assign(vmin.size(), -1e30f);
  for (int z = 0; z < count.z; ++z)
    for (int y = 0; y < count.y; ++y)
      for (int x = 0; x < count.x; ++x) {
        const Box3 world{{planes[0][size_t(x)], planes[1][size_t(y)], planes[2][size_t(z)]},
                         {planes[0][size_t(x) + 1], planes[1][size_t(y) + 1], planes[2][size_t(z) + 1]}};
        bool present = false;
        const IndexBox box = intersect(fieldBoxOf(part.grid, world, present), part.stored);
        if (!present || glm::any(glm::lessThan(box.hi, box.lo))) continue;
        const size_t i = size_t(x) + size_t(count.x) * (size_t(y) + size_t(count.y) * z);
        float lo = 1e30f, hi = -1e30f;
        for (int k = box.lo.z; k <= box.hi.z; ++k)
          for (int j = box.lo.y; j <= box.hi.y; ++j) {
            const float* row = part.samples->data() + size_t(box.lo.x - part.stored.lo.x) +
                               size_t(n.x) * (size_t(j - part.stored.lo.y) + size_t(n.y) * size_t(k - part.stored.lo.z));
            widenRange(row, size_t(box.hi.x - box.lo.x + 1), lo, hi);
          }
        vmin[i] = lo;
        vmax[i] = hi;
      }
}

}  // namespace sortlast
