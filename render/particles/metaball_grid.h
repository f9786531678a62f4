#pragma once
// The particle grid the metaball grid ray caster (render/particles/metaball_grid_renderer.h) walks: a
// uniform grid of cells over a brick's bound, each cell listing every particle whose sphere of
// influence (radius h, slightly padded) reaches into it, in the particles' original order. A
// sample point's field is then the sum over its cell's list alone, in global particle order: the
// same particles in the same order as the billboard method adds them (particles out of reach add
// exactly 0), and the same on every rank, since a brick's particles and bound do not depend on
// the rank count. Pure CPU: unit-tested without GL.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "common/box.h"

namespace sortlast {

struct ParticleGrid {
  glm::vec3 lo{0.0f};               // corner of cell (0, 0, 0), as the shader sees it
  float cell = 1.0f;                // cell edge
  glm::ivec3 dims{0};               // cells per axis; cell (x, y, z) is number (z dims.y + y) dims.x + x
  std::vector<uint32_t> offsets;    // dims.x dims.y dims.z + 1: cell i lists items[offsets[i], offsets[i+1])
  std::vector<uint32_t> items;      // particle indices, ascending within each cell
  size_t cellCount() const { return size_t(dims.x) * dims.y * dims.z; }
};

// Margin added to h when binning: a sample point the shader computes in float may lie this far
// outside the cell it is assigned to (rounding near a face), and must still find every particle
// within h of it in that cell's list. 1% of h is far above float rounding at any sane scale and
// costs about 2% more list entries.
constexpr double kGridPad = 0.01;

// Cells of edge `cell` over `bound` (which must hold every point of the brick where the
// particles' field can be non-zero) plus a margin of kGridPad h. The renderer uses cells of h/2:
// a particle then lands in about 84 cells (sphere-cube overlap test). `max_cells` bounds
// dims.x dims.y dims.z: the edge grows (x1.25 steps) until it fits.
// `reach` (optional, one per particle): each particle's own reach instead of h (anisotropic
// metaballs: the longest semi-axis of its ellipsoid), padded by kGridPad h likewise.
// `axes` (optional, with `reach`): each particle's ellipsoid semi-axes (columns, orthogonal, world
// units; ParticleKernel::axes): a particle is then listed only in the cells of its ellipsoid's
// bounding box that pass a separating-axis test along each semi-axis as well as the ball test
// (a superset of the cells the padded ellipsoid meets: a disc's slab, not its bounding ball).
ParticleGrid buildParticleGrid(const std::vector<glm::vec3>& particles, const Box3& bound, double h,
                               double cell, size_t max_cells = size_t(1) << 24,
                               const std::vector<float>* reach = nullptr,
                               const std::vector<glm::mat3>* axes = nullptr);

}  // namespace sortlast
