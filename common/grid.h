#pragma once
// Geometry of the uniform grid: sample (i,j,k) sits at world position (ijk - (dims-1)/2) * spacing,
// so the volume is centred on the origin and the field (trilinear between samples) is defined on
// the box spanned by the first and last samples.
#include <glm/glm.hpp>

#include "common/box.h"

namespace sortlast {

struct GridGeometry {
  glm::ivec3 dims{0};
  glm::dvec3 spacing{1.0};

  glm::dvec3 worldOfIndex(const glm::dvec3& ijk) const {
    return (ijk - 0.5 * glm::dvec3(dims - 1)) * spacing;
  }
  glm::dvec3 indexOfWorld(const glm::dvec3& p) const {
    return p / spacing + 0.5 * glm::dvec3(dims - 1);
  }
  Box3 worldBox() const { return {worldOfIndex(glm::dvec3(0.0)), worldOfIndex(glm::dvec3(dims - 1))}; }
  Box3 worldBoxOf(const IndexBox& b) const {
    return {worldOfIndex(glm::dvec3(b.lo)), worldOfIndex(glm::dvec3(b.hi))};
  }
  double minSpacing() const { return glm::min(spacing.x, glm::min(spacing.y, spacing.z)); }
  double largestExtent() const {
    glm::dvec3 e = worldBox().extent();
    return glm::max(e.x, glm::max(e.y, e.z));
  }
  long long sampleCount() const { return 1LL * dims.x * dims.y * dims.z; }
};

}  // namespace sortlast
