#pragma once
// The glow of a scene's emitters along one ray, in double: the reference path
// (glow/glow_integral.h's closed form, which tests/unit/glow_test.cpp checks against quadrature
// to 1e-6). Only the part of the ray inside `box` counts (the integral along an unbounded ray
// diverges).
#include <glm/glm.hpp>
#include <vector>

#include "common/box.h"
#include "glow/glow_field.h"
#include "scene/glow_scene.h"

namespace sortlast {

struct GlowRays {
  std::vector<GlowEmitter> emitters;
  double eps = 0.01;
  double intensity = 1.0;
  Box3 box;

  GlowRays(const GlowSpec& spec, const Box3& box, int frame);
  // intensity * sum of colour * int E over [ta, tb] clipped to the box; d of unit length.
  glm::dvec3 radiance(const glm::dvec3& o, const glm::dvec3& d, double ta, double tb) const;
  // The ray's span inside the box (false: it misses), t >= 0.
  bool span(const glm::dvec3& o, const glm::dvec3& d, double& t0, double& t1) const;
};

}  // namespace sortlast
