// Procedural volumes: the built-in default scene ("blobs": shells and blobs with sharp and smooth
// parts, worth a first look) and the Marschner-Lobb test function (Marschner & Lobb 1994), whose
// fine ripples expose any reconstruction or seam error.
#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.h"
#include "io/volume_source.h"

namespace sortlast {

namespace {
constexpr double kPi = 3.14159265358979323846;

double blobs(const glm::dvec3& u) {
  // Three Gaussian blobs, a thin spherical shell and a torus around the centre.
  auto gauss = [&](glm::dvec3 c, double s) {
    glm::dvec3 d = u - c;
    return std::exp(-glm::dot(d, d) / (2 * s * s));
  };
  double v = 0.9 * gauss({0.35, 0.3, 0.1}, 0.12) + 0.7 * gauss({-0.4, -0.2, 0.3}, 0.18) +
             0.55 * gauss({0.1, -0.45, -0.4}, 0.1);
  double r = glm::length(u);
  v += 0.32 * std::exp(-std::pow((r - 0.8) / 0.03, 2.0));  // shell
  double ring = std::hypot(std::hypot(u.x, u.z) - 0.5, u.y);
  v += 0.65 * std::exp(-std::pow(ring / 0.07, 2.0));  // torus
  return std::min(v, 1.0);
}

double marschnerLobb(const glm::dvec3& u) {
  const double fm = 6.0, alpha = 0.25;
  double r = std::sqrt(u.x * u.x + u.y * u.y);
  double rho_r = std::cos(2 * kPi * fm * std::cos(kPi * r / 2));
  return (1.0 - std::sin(kPi * u.z / 2) + alpha * (1.0 + rho_r)) / (2.0 * (1.0 + alpha));
}

double sphere(const glm::dvec3& u) { return std::clamp(1.0 - glm::length(u), 0.0, 1.0); }
}  // namespace

double proceduralValue(const std::string& name, const glm::dvec3& u) {
  if (name == "blobs") return blobs(u);
  if (name == "marschner_lobb") return marschnerLobb(u);
  if (name == "sphere") return sphere(u);
  throw InputError("volume.procedural: unknown field '" + name +
                   "' (known: blobs, marschner_lobb, sphere)");
}

}  // namespace sortlast
