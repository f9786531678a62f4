#include "subdiv/subdiv_shading.h"

#include <algorithm>
#include <cmath>

namespace sortlast {

glm::dvec3 stripeAxis(const glm::dvec3& light_direction) {
  const glm::dvec3 light = glm::normalize(light_direction);
  const glm::dvec3 other = std::abs(light.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(light, other));
}

glm::dvec3 shadeLimitPoint(const SubdivShading& s, const glm::dvec3& centre, double size,
                           const glm::dvec3& eye, const glm::dvec3& p, const glm::dvec3& n) {
  const glm::dvec3 view = glm::normalize(p - eye);
  glm::dvec3 rgb;
  if (s.mode == "reflection_lines") {
    // The reflected view ray against a square planar light 8 sizes wide, facing the surface from
    // 2 sizes beyond its centre; stripe edges ramp over 4 % of a period (see the shader).
    const glm::dvec3 light = glm::normalize(s.light_direction), axis = stripeAxis(s.light_direction);
    const glm::dvec3 r = glm::reflect(view, n);
    const double facing = glm::dot(r, light);
    double lit = 0.0;
    if (facing > 1e-6) {
      const glm::dvec3 x = p + r * (glm::dot(centre + 2.0 * size * light - p, light) / facing);
      const glm::dvec3 along = x - centre;
      const double a = glm::dot(along, axis) / (8.0 * size);
      const double b = glm::dot(along, glm::cross(light, axis)) / (8.0 * size);
      const double c = double(s.stripes) * (a + 0.5), f = c - std::floor(c);
      const double w = s.stripe_width;
      const double d = f < w ? std::min(f, w - f) : -std::min(f - w, 1.0 - f);
      if (std::abs(a) < 0.5 && std::abs(b) < 0.5) lit = std::clamp(d / 0.04 + 0.5, 0.0, 1.0);
    }
    rgb = s.colour * (0.12 + 0.88 * lit);
  } else {
    const double diffuse = std::abs(glm::dot(n, view));
    const double specular = std::pow(diffuse, 40.0);  // headlight: the half vector is the view
    rgb = s.colour * (0.15 + 0.85 * diffuse) + 0.25 * glm::dvec3(specular);
  }
  return glm::clamp(rgb, 0.0, 1.0);
}

}  // namespace sortlast
