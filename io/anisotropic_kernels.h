#pragma once
// Smoothed anisotropic metaballs (Kanamori and Nishita, ../shared/PAPERS.md §3, done in 3D): per
// particle a radius scaled by its density and an ellipsoid stretched along the local particle
// distribution, normalised so that every particle carries the same mass. Pure CPU, no GL: the
// grid ray caster (render/particles/metaball_grid_renderer.cpp) and the CPU reference
// (reference/metaball_reference.cpp) evaluate the field from the same float kernels.
//
// Per particle i, with the neighbours j within h_n (i itself included) and the paper's
// 6th-degree weight g(r) = (1 - r^2/h_n^2)^3:
//   rho_i = sum_j g_j                        (unnormalised: a lone particle has rho = 1)
//   s     = smoothstep(rho_i; rho_splash, rho_surface)
//   R_i   = (1 - s) R_splash + s R_surface    (R in units of h)
//   mu_i  = sum_j g_j c_j / sum_j g_j
//   x_i   = (1 - lambda) c_i + lambda mu_i  (the kernel's centre: Yu and Turk's smoothed
//                                            position; lambda = position_smoothing)
//   S_i   = sum_j g_j (c_j - mu)(c_j - mu)^T / |c_j - mu|^2 / sum_j g_j   (the paper's Sigma)
// (Each term of S_i is a unit direction whatever the neighbour's distance from the mean; we fade
// in the directions of neighbours within 0.1 h_n of it, which rounding alone would orient.)
// S_i has trace 1 (each term is a unit direction's outer product); we use 3 S_i / trace so that
// an even spread of directions gives the identity (the paper's R is then our R times sqrt(3)).
// Only surface particles are smoothed (the paper): the shape is blended to the sphere by s,
//   Sigma_i = (1 - s) I + s 3 S_i / trace(S_i),
// whose eigenvalues sigma_1 >= sigma_2 >= sigma_3 are clamped to sigma_k >= sigma_1 / k^2 (k =
// max_axis_ratio: no axis is shorter than 1/k of the longest), so the ellipsoid never
// degenerates (a line of particles, rank 1, becomes a cigar of axis ratio k). No usable
// direction (no neighbour, or all neighbours on the mean): a sphere. Axes R_i h sqrt(sigma_k).
// The kernel sits at the smoothed centre x_i, not at c_i: the paper's normalisation integrates
// each ellipsoid around mu_i, and Yu and Turk (whose covariance the paper follows) place their
// kernels at x_i with lambda about 0.9. Inside the fluid mu_i = c_i on average; in the surface
// layer mu_i lies inward, so the layer's bumps (one per particle) flatten. |x_i - c_i| <
// lambda h_n: the reach bound grows by that much.
// The field of particle i at offset r = x - x_i is
//   P_i(r) = C_i (1 - |A_i r| / h)^2  for |A_i r| <= h,  A_i = Sigma_i^(-1/2) / R_i,
//   C_i = (R_0 / R_i)^3 / sqrt(det Sigma_i),  R_0 = R_splash,
// the normalisation: the integral of P_i is that of a sphere of radius R_0 h (exactly,
// for any radial profile: |A r| is an affine change of variables with Jacobian
// det A^-1 = R_i^3 sqrt(det Sigma)). The paper derives it for a Gaussian and uses it on its
// polynomial; same formula. A lone particle (s = 0) gets A = I / R_splash and C = 1 exactly:
// the round metaball of radius R_splash h.
//
// Every particle's kernel depends only on the particles within h_n of it, summed in ascending
// index order (the input's order, which is global order in every brick's list), so a particle
// gets the same kernel, bit for bit, from any subset of the set that holds its neighbourhood.
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace sortlast {

struct AnisotropicParams {
  double splash_scale = 1.0;    // R_splash / h
  double surface_scale = 1.5;   // R_surface / h
  double rho_splash = 3.0;      // at or below: splash (round, R_splash)
  double rho_surface = 6.0;     // at or above: surface or inside (smoothed, R_surface)
  double neighbourhood = 2.5;   // h_n / h
  double max_axis_ratio = 3.0;  // k: longest axis / shortest axis at most
  double position_smoothing = 0.0;  // lambda: kernel centre (1 - lambda) c_i + lambda mu_i
  bool operator==(const AnisotropicParams&) const = default;
};

// The rule between the keys: rho_surface above rho_splash (each key's own range is in the scene
// key table, scene/scene_keys.cpp). Throws InputError naming particles.anisotropic.rho_surface.
void validateAnisotropic(const AnisotropicParams& p);

// The furthest a particle's field can reach from its position c_i, in units of h: the centre's
// shift lambda h_n plus the longest axis R sqrt(sigma_1) <= max(R_splash, R_surface) sqrt(3)
// (sigma_1 <= trace = 3).
double anisotropicReachBound(const AnisotropicParams& p);

struct ParticleKernel {
  glm::vec3 centre{0.0f};  // x_i, the smoothed centre the field is evaluated around
  glm::mat3 a{1.0f};   // A_i (symmetric): the ellipsoid frame; |A r| <= h inside the support
  float c = 1.0f;      // C_i, the mass normalisation
  float reach = 1.0f;  // the longest semi-axis (world units): the support's bounding sphere
                       // around `centre`
  glm::mat3 axes{0.0f};  // the semi-axes as vectors (columns, world units: R h sqrt(sigma_k)
                        // along eigenvector k), for bounding the support tighter than `reach`
  float s = 0.0f;      // the surface fraction smoothstep(rho) (0: splash, 1: surface)
  float rho = 1.0f;    // the density rho_i
};

// Kernels for every particle of `positions` (influence radius h, world units). A particle whose
// neighbourhood (radius h_n) is not wholly in `positions` gets a kernel from the part there.
std::vector<ParticleKernel> computeAnisotropicKernels(const std::vector<glm::vec3>& positions,
                                                      double h, const AnisotropicParams& p);

// The longest reach of `kernels` (world units); 0 for none.
double maxReach(const std::vector<ParticleKernel>& kernels);

}  // namespace sortlast
