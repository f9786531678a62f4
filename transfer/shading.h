#pragma once
// Gradient shading of volume samples (render.shading): Blinn-Phong with a headlight, the one model
// the GL renderers (render/volume/volume_shading.h) and the CPU reference (reference/reference.cpp) share.
//
// The light sits at the eye, so at a sample seen along unit ray direction d the light direction
// is l = -d and the half vector is l too. Volume isosurfaces face both ways, so the model is
// two-sided: with n the unit gradient and cos = |n . l|, a sample of transfer-function colour c
// emits
//   c' = clamp(c (ka + kd cos) + ks cos^p, 0, 1)   (white light; clamped per channel)
// and its opacity is unchanged (shading changes colour, never what is seen through).
//
// The gradient is the central difference of the trilinear field one voxel either side along each
// grid axis, (f(u + e_a) - f(u - e_a)) / (2 spacing_a) in world units, with the index u clamped to
// the grid where it leaves it (one-sided at the data set's faces). Where the field is flat the
// normal means nothing: a gradient at or below the floor (kFlatGradient of the transfer
// function's value range per smallest voxel spacing) leaves the colour unshaded, at twice the
// floor and above it is fully shaded, and in between the two colours mix linearly, so the choice
// is continuous and float rounding cannot flip a pixel between them.
#include <array>
#include <glm/glm.hpp>

namespace sortlast {

struct Shading {
  bool enabled = false;
  double ambient = 0.3;    // ka
  double diffuse = 0.7;    // kd
  double specular = 0.2;   // ks
  double shininess = 20;   // p
};

// The gradient floor, per smallest voxel spacing, as a fraction of the transfer function's range.
inline constexpr double kFlatGradient = 1e-3;

// The floor in data units per world unit: kFlatGradient * (hi - lo) / smallest spacing (a range of
// zero counts as 1, so the floor stays positive).
double flatGradient(double range_lo, double range_hi, const glm::dvec3& spacing);

// c' of a sample of colour `c` with world gradient `g`, seen along unit direction `dir`; `flat`
// from flatGradient(). Computed as c + w (shaded - c), so a weight of 0 returns c exactly.
std::array<double, 3> shadeSample(const std::array<double, 3>& c, const glm::dvec3& g,
                                  const glm::dvec3& dir, const Shading& s, double flat);

}  // namespace sortlast
