#pragma once
// The glow integral by adaptive quadrature of the point field (glow/glow_field.h): the check on
// the closed forms of glow/glow_integral.h, which it shares nothing with but the field.
#include <glm/glm.hpp>

#include "glow/glow_field.h"

namespace sortlast {

struct QuadratureResult {
  double value = 0.0;
  double error =
      0.0;  // Boost's estimate: the change between its last two levels, summed over pieces
};

// int_{s0}^{s1} E(o + s u) ds, u of unit length, by tanh-sinh quadrature (Boost.Math), refined
// level by level to a relative tolerance of 1e-13. The interval is first cut where the field has a
// jump or a peak of width eps (the crossing of the plane, the closest points to M and to the axis),
// so each piece is smooth with its one sharp feature at an end, where tanh-sinh's nodes crowd
// doubly exponentially (an adaptive Gauss-Kronrod, tried first, bisected towards a 1e-6-wide peak
// in a 1e4-long segment for minutes).
QuadratureResult glowQuadrature(const GlowEmitter& e, double eps, const glm::dvec3& o,
                                const glm::dvec3& u, double s0, double s1);

}  // namespace sortlast
