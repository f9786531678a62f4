#include "reference/glow_reference.h"

#include <algorithm>

#include "glow/glow_integral.h"

namespace sortlast {

GlowRays::GlowRays(const GlowSpec& spec, const Box3& b, int frame)
    : emitters(spec.emittersAt(frame)), eps(spec.core_radius), intensity(spec.intensity), box(b) {}

bool GlowRays::span(const glm::dvec3& o, const glm::dvec3& d, double& t0, double& t1) const {
  if (!intersectRayBox(o, d, box, t0, t1)) return false;
  t0 = std::max(t0, 0.0);
  return t1 > t0;
}

glm::dvec3 GlowRays::radiance(const glm::dvec3& o, const glm::dvec3& d, double ta,
                              double tb) const {
  double g0, g1;
  glm::dvec3 sum(0.0);
  if (!span(o, d, g0, g1)) return sum;
  ta = std::max(ta, g0);
  tb = std::min(tb, g1);
  if (!(tb > ta)) return sum;
  for (const GlowEmitter& e : emitters) sum += e.colour * glowSegment(e, eps, o, d, ta, tb);
  return intensity * sum;
}

}  // namespace sortlast
