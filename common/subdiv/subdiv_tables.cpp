#include "common/subdiv/subdiv_tables.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace sortlast {

SubdivTables buildTables(const SubdivSurface& surface) {
  const auto start = std::chrono::steady_clock::now();
  SubdivTables t;
  t.faces.resize(surface.patchCount());
  auto append = [&](int face, int n, int k) {
    for (const bool tangent : {false, true}) {
      auto& out = tangent ? t.tangents : t.positions;
      for (const glm::dvec3& p : surface.controlPoints(face, n, k, tangent)) out.emplace_back(glm::vec3(p), 0.0f);
    }
  };
  int sets = 0;
  for (int f = 0; f < surface.patchCount(); ++f) {
    auto& e = t.faces[f];
    e.firstSet = sets;
    e.regular = surface.regular(f) ? 1 : 0;
    if (e.regular) {
      append(f, 0, 0);
      ++sets;
      continue;
    }
    std::vector<std::array<glm::dvec3, 16>> positions, tangents;
    surface.subPatches(f, kTableLevels, positions, tangents);
    for (const auto& set : positions)
      for (const glm::dvec3& p : set) t.positions.emplace_back(glm::vec3(p), 0.0f);
    for (const auto& set : tangents)
      for (const glm::dvec3& p : set) t.tangents.emplace_back(glm::vec3(p), 0.0f);
    sets += kTableLevels * 3;
  }
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

FloatLimitPoint evaluateTables(const SubdivTables& tables, int face, float u, float v) {
  const auto& e = tables.faces[face];
  int set = e.firstSet;
  float s = u, t = v;
  if (!e.regular) {
    const float m = std::max(u, v);
    int n = kTableLevels;
    if (m > 0.0f) n = std::clamp(int(std::floor(-std::log2(m))) + 1, 1, kTableLevels);
    const float su = std::ldexp(u, n), sv = std::ldexp(v, n);
    int k;
    if (su >= 1.0f && sv >= 1.0f) k = 2;
    else if (su >= 1.0f) k = 1;
    else if (sv >= 1.0f) k = 3;
    else k = su >= sv ? 1 : 3;
    s = su - (k != 3 ? 1.0f : 0.0f);
    t = sv - (k != 1 ? 1.0f : 0.0f);
    set += (n - 1) * 3 + (k - 1);
  }
  float bs[4], dbs[4], bt[4], dbt[4];
  bsplineBasis(s, bs, dbs);
  bsplineBasis(t, bt, dbt);
  glm::vec3 p(0.0f), ds(0.0f), dt(0.0f);
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      const int i = set * 16 + b * 4 + a;
      p += bs[a] * bt[b] * glm::vec3(tables.positions[i]);
      ds += dbs[a] * bt[b] * glm::vec3(tables.tangents[i]);
      dt += bs[a] * dbt[b] * glm::vec3(tables.tangents[i]);
    }
  return {p, glm::normalize(glm::cross(ds, dt))};
}

}  // namespace sortlast
