#include "render/particles/metaball_grid.h"

#include <algorithm>
#include <cmath>

namespace sortlast {

namespace {

// Calls f(cell number, the cell's low corner) for every cell of g inside the box p +- half that
// the ball (p, r) overlaps (the closed cell box within distance r of p): the one walk of the
// round and the anisotropic kernels' cell lists.
template <class F>
void forCellsNear(const ParticleGrid& g, const glm::vec3& p, const glm::vec3& half, float r, F&& f) {
  glm::vec3 a = (p - half - g.lo) / g.cell, b = (p + half - g.lo) / g.cell;
  glm::ivec3 lo = glm::max(glm::ivec3(glm::floor(a)), glm::ivec3(0));
  glm::ivec3 hi = glm::min(glm::ivec3(glm::floor(b)), g.dims - 1);
  if (glm::any(glm::greaterThan(lo, hi))) return;
  const float r2 = r * r;
  for (int z = lo.z; z <= hi.z; ++z) {
    float cz = g.lo.z + float(z) * g.cell;
    float dz = std::max({cz - p.z, 0.0f, p.z - (cz + g.cell)});
    for (int y = lo.y; y <= hi.y; ++y) {
      float cy = g.lo.y + float(y) * g.cell;
      float dy = std::max({cy - p.y, 0.0f, p.y - (cy + g.cell)});
      float dzy = dz * dz + dy * dy;
      if (dzy > r2) continue;
      size_t row = (size_t(z) * g.dims.y + y) * g.dims.x;
      for (int x = lo.x; x <= hi.x; ++x) {
        float cx = g.lo.x + float(x) * g.cell;
        float dx = std::max({cx - p.x, 0.0f, p.x - (cx + g.cell)});
        if (dzy + dx * dx <= r2) f(row + size_t(x), glm::vec3(cx, cy, cz));
      }
    }
  }
}

// Calls f(cell number) for every cell of g that the ball (p, r) overlaps.
template <class F>
void forCellsOf(const ParticleGrid& g, const glm::vec3& p, float r, F&& f) {
  forCellsNear(g, p, glm::vec3(r), r, [&](size_t cell, const glm::vec3&) { f(cell); });
}

// Calls f(cell number) for every cell of g that the ellipsoid {p + M v : |v| <= 1}, grown by
// `pad`, may overlap, M's columns being its semi-axes (orthogonal vectors) and r >= the longest
// one plus pad: the cells of its bounding box that pass the ball test of forCellsOf and, along
// each semi-axis direction, the separating-axis test (the cell's projection within the
// ellipsoid's extent plus pad). Conservative (a cell near the ellipsoid's rim may pass without
// touching it), never missing one: a flat disc of 3:1 lists its thin slab of cells, not a ball.
template <class F>
void forCellsOfEllipsoid(const ParticleGrid& g, const glm::vec3& p, float r, const glm::mat3& m,
                         float pad, F&& f) {
  glm::vec3 half, n[3];
  float len[3];
  for (int i = 0; i < 3; ++i) {
    half[i] = std::sqrt(m[0][i] * m[0][i] + m[1][i] * m[1][i] + m[2][i] * m[2][i]) + pad;
    len[i] = glm::length(m[i]);
    n[i] = len[i] > 0.0f ? m[i] / len[i] : glm::vec3(0.0f);
  }
  half = glm::min(half, glm::vec3(r));
  const float hc = 0.5f * g.cell;
  float box[3], limit[3];
  for (int k = 0; k < 3; ++k) {
    box[k] = hc * (std::abs(n[k].x) + std::abs(n[k].y) + std::abs(n[k].z));
    // A little slack for the float arithmetic of the test itself.
    limit[k] = (len[k] + pad + box[k]) * (1.0f + 1e-5f) + 1e-6f * g.cell;
  }
  forCellsNear(g, p, half, r, [&](size_t cell, const glm::vec3& corner) {
    glm::vec3 v = corner + hc - p;
    if (std::abs(glm::dot(n[0], v)) > limit[0] || std::abs(glm::dot(n[1], v)) > limit[1] ||
        std::abs(glm::dot(n[2], v)) > limit[2])
      return;
    f(cell);
  });
}

}  // namespace

ParticleGrid buildParticleGrid(const std::vector<glm::vec3>& particles, const Box3& bound, double h,
                               double cell, size_t max_cells, const std::vector<float>* reach,
                               const std::vector<glm::mat3>* axes) {
  ParticleGrid g;
  // A margin of kGridPad h around the bound: the shader computes where a ray enters and leaves
  // the grid in float, and a brick face that the bound shares must lie strictly inside, or the
  // sample at the box exit (or entry) could fall outside and be skipped.
  const double margin = kGridPad * h;
  g.lo = glm::vec3(bound.lo - margin);
  glm::dvec3 extent = glm::max(bound.hi - bound.lo, glm::dvec3(0.0)) + 2.0 * margin;
  for (;;) {
    g.cell = float(cell);
    g.dims = glm::max(glm::ivec3(glm::ceil(extent / cell)), glm::ivec3(1));
    if (g.cellCount() <= max_cells) break;
    cell *= 1.25;
  }
  const float r = float(h * (1.0 + kGridPad));
  auto radius = [&](size_t i) { return reach ? float((*reach)[i] + h * kGridPad) : r; };
  // Counting sort: count, prefix sums, fill. Particles are visited in order, so every cell's
  // list comes out ascending.
  g.offsets.assign(g.cellCount() + 1, 0);
  const float pad = float(h * kGridPad);
  auto cellsOf = [&](size_t i, auto&& f) {
    if (axes)
      forCellsOfEllipsoid(g, particles[i], radius(i), (*axes)[i], pad, f);
    else
      forCellsOf(g, particles[i], radius(i), f);
  };
  for (size_t i = 0; i < particles.size(); ++i) cellsOf(i, [&](size_t c) { ++g.offsets[c + 1]; });
  for (size_t c = 0; c < g.cellCount(); ++c) g.offsets[c + 1] += g.offsets[c];
  g.items.resize(g.offsets.back());
  std::vector<uint32_t> cursor(g.offsets.begin(), g.offsets.end() - 1);
  for (size_t i = 0; i < particles.size(); ++i)
    cellsOf(i, [&](size_t c) { g.items[cursor[c]++] = uint32_t(i); });
  return g;
}

}  // namespace sortlast
