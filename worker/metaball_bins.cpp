#include "worker/metaball_bins.h"

#include <cmath>

namespace sortlast {

ParticleBins binParticles(const std::vector<glm::vec3>& particles, double cell, size_t max_cells) {
  ParticleBins b;
  if (particles.empty()) {
    b.dims = glm::ivec3(1);
    b.offsets.assign(2, 0);
    return b;
  }
  glm::vec3 lo = particles[0], hi = particles[0];
  for (const glm::vec3& p : particles) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  b.lo = lo;
  for (;;) {
    b.cell = float(cell);
    // One more cell than the extent needs: a centre on the top face still has a cell.
    b.dims = glm::ivec3(glm::floor((hi - lo) / b.cell)) + 1;
    if (size_t(b.dims.x) * b.dims.y * b.dims.z <= max_cells) break;
    cell *= 1.25;
  }
  auto cellOf = [&](const glm::vec3& p) {
    glm::ivec3 c = glm::clamp(glm::ivec3(glm::floor((p - b.lo) / b.cell)), glm::ivec3(0), b.dims - 1);
    return (size_t(c.z) * b.dims.y + c.y) * b.dims.x + c.x;
  };
  size_t cells = size_t(b.dims.x) * b.dims.y * b.dims.z;
  b.offsets.assign(cells + 1, 0);
  for (const glm::vec3& p : particles) ++b.offsets[cellOf(p) + 1];
  for (size_t c = 0; c < cells; ++c) b.offsets[c + 1] += b.offsets[c];
  b.entries.resize(particles.size());
  std::vector<uint32_t> cursor(b.offsets.begin(), b.offsets.end() - 1);
  for (size_t i = 0; i < particles.size(); ++i)
    b.entries[cursor[cellOf(particles[i])]++] = glm::vec4(particles[i], float(i));
  return b;
}

}  // namespace sortlast
