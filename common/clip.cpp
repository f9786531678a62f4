#include "common/clip.h"

#include <algorithm>

namespace sortlast {

std::vector<ClipPlane> ClipRegion::halfSpaces() const {
  std::vector<ClipPlane> out = planes;
  if (has_box)
    for (int a = 0; a < 3; ++a) {
      glm::dvec3 n(0.0);
      n[a] = -1.0;
      out.push_back({n, -box.lo[a]});
      n[a] = 1.0;
      out.push_back({n, box.hi[a]});
    }
  return out;
}

bool ClipRegion::culls(const Box3& b) const {
  if (isEmpty(b)) return true;
  if (has_box && isEmpty(intersect(b, box))) return true;
  for (const ClipPlane& p : planes) {
    // The box's corner least far along n: if even it is beyond the plane, all of b is.
    glm::dvec3 c;
    for (int a = 0; a < 3; ++a) c[a] = p.normal[a] >= 0.0 ? b.lo[a] : b.hi[a];
    if (glm::dot(p.normal, c) > p.offset) return true;
  }
  return false;
}

Box3 ClipRegion::bound(const Box3& b) const { return has_box ? intersect(b, box) : b; }

void clipSpan(const ClipRegion& clip, const glm::dvec3& o, const glm::dvec3& d, double& t0, double& t1) {
  for (const ClipPlane& p : clip.halfSpaces()) {
    const double nd = glm::dot(p.normal, d), gap = p.offset - glm::dot(p.normal, o);
    if (nd > 0.0)
      t1 = std::min(t1, gap / nd);
    else if (nd < 0.0)
      t0 = std::max(t0, gap / nd);
    else if (gap < 0.0)
      t1 = std::min(t1, t0);  // parallel to the plane, on its far side: nothing kept
  }
}

}  // namespace sortlast
