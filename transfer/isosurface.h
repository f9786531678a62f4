#pragma once
// Isosurfaces of the volume (render.blend: isosurface): the surfaces where the trilinear field
// equals an isovalue, each drawn in its own colour and opacity. The one definition the GL ray
// caster (render/volume/raycast_isosurface.frag.glsl) and the CPU reference
// (reference/isosurface_reference.h) share: what an isovalue is and how a hit is shaded.
//
// A ray crosses isovalue v where the predicate "field >= v" changes along it (a touch without a
// change of side is no crossing). Every crossing is a surface: a hit of colour c and opacity a
// adds (1 - A) (a c', a) to what the ray holds (front to back; A its opacity so far), c' the
// colour shaded with the field's exact gradient g at the hit (the derivative of the trilinear
// interpolant in the hit's cell, in world units):
//   c' = clamp(c (ka + kd cos) + ks cos^p, 0, 1),  cos = |g . d| / |g|  (1 where g = 0),
// the headlight Blinn-Phong of transfer/shading.h, two-sided, with render.shading_*'s
// coefficients; always fully shaded (the volume shading's flat-gradient floor does not apply:
// a crossing of a non-constant field has a gradient, and a constant one has no crossing).
#include <glm/glm.hpp>
#include <vector>

#include "transfer/shading.h"

namespace sortlast {

struct Isovalue {
  double value = 0.0;
  glm::dvec3 colour{1.0};
  double opacity = 1.0;  // in [0, 1]; 1: opaque, the ray ends there
};

// At most this many isovalues (the GL program holds them in a uniform array).
inline constexpr int kMaxIsovalues = 8;

// c' above for a hit of colour c with world gradient g, seen along unit direction d.
glm::dvec3 shadeIsoHit(const glm::dvec3& c, const glm::dvec3& g, const glm::dvec3& d, const Shading& s);

}  // namespace sortlast
