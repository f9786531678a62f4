#include "common/box.h"

#include <algorithm>
#include <limits>

namespace sortlast {

bool intersectRayBox(const glm::dvec3& origin, const glm::dvec3& dir, const Box3& box, double& t0,
                     double& t1) {
  t0 = -std::numeric_limits<double>::infinity();
  t1 = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0) {
      if (origin[a] < box.lo[a] || origin[a] > box.hi[a]) return false;
      continue;
    }
    double inv = 1.0 / dir[a];
    double ta = (box.lo[a] - origin[a]) * inv, tb = (box.hi[a] - origin[a]) * inv;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

}  // namespace sortlast
