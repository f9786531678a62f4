#include "subdiv/subdiv_coarse.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <string>

#include "common/error.h"

namespace sortlast {

namespace {

int cutsPerSide(const SubdivSurface& surface, int level, const char* key) {
  const int lowest = surface.control().levels;
  if (level < lowest || level > 6)
    throw InputError(std::string(key) + ": " + std::to_string(level) + " is out of range; surface '" +
                     surface.control().mesh.name + "' needs " + std::to_string(lowest) +
                     " to 6 (its control mesh is " + std::to_string(lowest) +
                     " Catmull-Clark steps from the input)");
  return 1 << (level - lowest);
}

}  // namespace

CoarseMesh buildCoarseMesh(const SubdivSurface& surface, int level, const char* key) {
  const int m = cutsPerSide(surface, level, key);
  CoarseMesh out;
  out.level = level;
  const int row = m + 1;
  for (int f = 0; f < surface.patchCount(); ++f) {
    if (surface.hole(f)) continue;  // no limit surface there
    const unsigned base = static_cast<unsigned>(out.vertices.size());
    // Vertices are per face (not shared), so each carries its own face's (u, v).
    for (int j = 0; j <= m; ++j)
      for (int i = 0; i <= m; ++i) {
        const double u = double(i) / m, v = double(j) / m;
        out.vertices.push_back({glm::vec3(surface.evaluate(f, u, v).position), float(u), float(v), f});
      }
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const unsigned a = base + j * row + i, b = a + 1, c = a + row + 1, d = a + row;
        out.triangles.insert(out.triangles.end(), {a, b, c, a, c, d});
      }
  }
  return out;
}

double coarseDeviation(const SubdivSurface& surface, int level) {
  const int m = cutsPerSide(surface, level, "level");
  double worst = 0;
  for (int f = 0; f < surface.patchCount(); ++f)
    for (int j = 0; j < m && !surface.hole(f); ++j)
      for (int i = 0; i < m; ++i) {
        glm::dvec3 corner[4];
        for (int c = 0; c < 4; ++c)
          corner[c] = surface.evaluate(f, double(i + (c == 1 || c == 2)) / m, double(j + (c >= 2)) / m).position;
        for (int b = 0; b <= 4; ++b)
          for (int a = 0; a <= 4; ++a) {
            const double x = a / 4.0, y = b / 4.0;
            const glm::dvec3 flat = (1 - y) * ((1 - x) * corner[0] + x * corner[1]) + y * ((1 - x) * corner[3] + x * corner[2]);
            const glm::dvec3 exact = surface.evaluate(f, (i + x) / m, (j + y) / m).position;
            worst = std::max(worst, glm::length(flat - exact));
          }
      }
  return worst / surface.control().mesh.size();
}

}  // namespace sortlast
