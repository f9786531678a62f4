#pragma once
// The energy-wave field of one glow emitter (Abe and Watanabe 2010, ../shared/PAPERS.md §4), with a
// core radius eps that keeps it finite:
//   E(P) = b / sqrt(dist(P, axis)^2 + eps^2)   where (P - M) . D >= 0 (the side D points to: the
//                                              paper's eq. 3 "in the normal direction of plane I")
//   E(P) = a / sqrt(|P - M|^2 + eps^2)         elsewhere (the paper's eq. 2, the rounded back cap)
// The axis is the line through M along D. At the plane both distances are |P - M|, so a = b makes
// the field continuous. This file is the point field only: the quadrature reference samples it and
// glow/glow_integral.h integrates it in closed form.
#include <glm/glm.hpp>

namespace sortlast {

struct GlowEmitter {
  glm::dvec3 centre{0.0};         // M
  glm::dvec3 direction{1, 0, 0};  // D, unit length (the scene normalises it)
  double a = 1.0;                 // sphere strength (back side)
  double b = 1.0;                 // cylinder strength (D side)
  glm::dvec3 colour{1.0};         // radiance per unit of integrated field
};

// E(P) as above; eps > 0.
double glowField(const GlowEmitter& e, double eps, const glm::dvec3& p);

}  // namespace sortlast
