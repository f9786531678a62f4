#pragma once
// How a subdivision surface is shaded: the settings (scene keys `surfaces[i].shading`, ...) and the
// shading model itself in double, which the CPU reference (reference/surface_reference.h) uses and the
// GL renderer's fragment shader (render/surfaces/subdiv_renderer.cpp) mirrors line for line.
#include <glm/glm.hpp>
#include <string>

namespace sortlast {

struct SubdivShading {
  std::string mode = "headlight";  // headlight | reflection_lines
  glm::dvec3 colour{0.8, 0.8, 0.85};
  // reflection_lines: a planar light perpendicular to `light_direction` (from the surface's centre,
  // at 2 sizes), striped `stripes` times across its size with bright bands of `stripe_width` (0..1)
  int stripes = 12;
  double stripe_width = 0.3;
  glm::dvec3 light_direction{0.0, 1.0, 0.0};
  // Newton steps per fragment moving its (u, v) onto the pixel's ray (0: the coarse fragment's
  // interpolated (u, v), as the paper does); a step that leaves the control face continues on
  // the face across that edge. Three: with two, the dense stripes of reflection lines near
  // grazing angles still moved by up to 27/255 between coarse levels 1 and 3 (pole5, 160^2).
  int newton_steps = 3;
};

// The colour (rgb in [0, 1], opaque) of limit point `p` with unit normal `n`, seen from `eye`, on a
// surface whose control mesh has centre `centre` and size `size` (diagonal of its bounds).
glm::dvec3 shadeLimitPoint(const SubdivShading& s, const glm::dvec3& centre, double size,
                           const glm::dvec3& eye, const glm::dvec3& p, const glm::dvec3& n);

// The axis the stripes run across: perpendicular to the light direction (as the shader takes it).
glm::dvec3 stripeAxis(const glm::dvec3& light_direction);

}  // namespace sortlast
