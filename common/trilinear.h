#pragma once
// Trilinear interpolation of the 8 corners of a cell, x first, then y, then z: the one formula the
// CPU samplers share (the reference's whole volume, the adaptive field, a brick's adaptive
// blocks), so they round identically. `corner(dx, dy, dz)` returns the corner value (dx, dy, dz
// in {0, 1}); `f` is the position inside the cell, each in [0, 1].
#include <glm/vec3.hpp>

namespace sortlast {

template <class Corner>
double trilinear(Corner&& corner, const double f[3]) {
  double c00 = corner(0, 0, 0) * (1 - f[0]) + corner(1, 0, 0) * f[0];
  double c10 = corner(0, 1, 0) * (1 - f[0]) + corner(1, 1, 0) * f[0];
  double c01 = corner(0, 0, 1) * (1 - f[0]) + corner(1, 0, 1) * f[0];
  double c11 = corner(0, 1, 1) * (1 - f[0]) + corner(1, 1, 1) * f[0];
  double c0 = c00 * (1 - f[1]) + c10 * f[1], c1 = c01 * (1 - f[1]) + c11 * f[1];
  return c0 * (1 - f[2]) + c1 * f[2];
}

// The gradient of a field in world units by central differences one sample apart on each axis:
// `at(u)` samples the field at index-space position u, `spacing` is the grid's sample spacing.
// The shading gradient of the CPU references (the whole volume's and a brick's segments alike).
template <class At>
glm::dvec3 centralGradient(const At& at, const glm::dvec3& u, const glm::dvec3& spacing) {
  glm::dvec3 g;
  for (int a = 0; a < 3; ++a) {
    glm::dvec3 e(0.0);
    e[a] = 1.0;
    g[a] = (at(u + e) - at(u - e)) / (2.0 * spacing[a]);
  }
  return g;
}

}  // namespace sortlast
