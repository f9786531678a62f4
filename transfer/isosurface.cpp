#include "transfer/isosurface.h"

#include <algorithm>
#include <cmath>

namespace sortlast {

glm::dvec3 shadeIsoHit(const glm::dvec3& c, const glm::dvec3& g, const glm::dvec3& d, const Shading& s) {
  const double len = glm::length(g);
  const double cosine = len > 0.0 ? std::min(std::abs(glm::dot(g, d)) / len, 1.0) : 1.0;
  glm::dvec3 out;
  for (int k = 0; k < 3; ++k)
    out[k] = std::clamp(c[k] * (s.ambient + s.diffuse * cosine) + s.specular * std::pow(cosine, s.shininess),
                        0.0, 1.0);
  return out;
}

}  // namespace sortlast
