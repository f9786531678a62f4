#pragma once
// Particles binned by centre into a uniform grid of cells (each particle in exactly one cell),
// for the tile march of the metaball grid ray caster (worker/metaball_grid_tile_shaders.h): a
// workgroup gathers the particles near a stretch of its rays from the cells around it. Within a
// cell the particles keep their order. Pure CPU.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace sortlast {

struct ParticleBins {
  glm::vec3 lo{0.0f};             // corner of cell (0, 0, 0)
  float cell = 1.0f;              // cell edge
  glm::ivec3 dims{0};             // cells per axis; cell (x, y, z) is number (z dims.y + y) dims.x + x
  std::vector<uint32_t> offsets;  // cell i holds entries[offsets[i], offsets[i+1])
  std::vector<glm::vec4> entries; // centre, and the particle's number as a float (exact below 2^24)
};

// Cells of edge `cell` (grown x1.25 until at most max_cells) over the particles' bounding box.
ParticleBins binParticles(const std::vector<glm::vec3>& particles, double cell,
                          size_t max_cells = size_t(1) << 22);

}  // namespace sortlast
