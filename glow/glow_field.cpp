#include "glow/glow_field.h"

#include <cmath>

namespace sortlast {

double glowField(const GlowEmitter& e, double eps, const glm::dvec3& p) {
  const glm::dvec3 w = p - e.centre;
  const double along = glm::dot(w, e.direction);
  if (along >= 0.0) {
    // Distance to the axis from the perpendicular part itself, not |w|^2 - along^2 (which cancels).
    const glm::dvec3 perp = w - along * e.direction;
    return e.b / std::sqrt(glm::dot(perp, perp) + eps * eps);
  }
  return e.a / std::sqrt(glm::dot(w, w) + eps * eps);
}

}  // namespace sortlast
