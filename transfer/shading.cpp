#include "transfer/shading.h"

#include <algorithm>
#include <cmath>

namespace sortlast {

double flatGradient(double range_lo, double range_hi, const glm::dvec3& spacing) {
  const double range = range_hi - range_lo;
  const double smallest = std::min({spacing.x, spacing.y, spacing.z});
  return kFlatGradient * (range > 0.0 ? range : 1.0) / smallest;
}

std::array<double, 3> shadeSample(const std::array<double, 3>& c, const glm::dvec3& g,
                                  const glm::dvec3& dir, const Shading& s, double flat) {
  const double len = glm::length(g);
  if (std::isnan(len)) return c;  // a gradient tap touches a missing sample: unshaded
  const double w = std::clamp(len / flat - 1.0, 0.0, 1.0);
  if (w == 0.0) return c;
  const double cosine = std::min(std::abs(glm::dot(g, dir)) / len, 1.0);
  const double diffuse = s.ambient + s.diffuse * cosine;
  const double highlight = s.specular * std::pow(cosine, s.shininess);
  std::array<double, 3> out;
  for (int k = 0; k < 3; ++k) {
    const double shaded = std::clamp(c[k] * diffuse + highlight, 0.0, 1.0);
    out[k] = c[k] + w * (shaded - c[k]);
  }
  return out;
}

}  // namespace sortlast
