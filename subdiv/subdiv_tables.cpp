#include "subdiv/subdiv_tables.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

namespace sortlast {

SubdivTables buildTables(const SubdivSurface& surface) {
  const auto start = std::chrono::steady_clock::now();
  SubdivTables t;
  t.faces.resize(surface.patchCount());
  int sets = 0;
  auto appendSets = [&](const std::vector<std::array<glm::dvec3, 16>>& positions,
                        const std::vector<std::array<glm::dvec3, 16>>& tangents) {
    for (const auto& set : positions)
      for (const glm::dvec3& p : set) t.positions.emplace_back(glm::vec3(p), 0.0f);
    for (const auto& set : tangents)
      for (const glm::dvec3& p : set) t.tangents.emplace_back(glm::vec3(p), 0.0f);
    sets += static_cast<int>(positions.size());
  };
  // A tree node's entry (at `entry`): a leaf's sets, or a split's four child entries appended.
  std::function<void(int, int)> emitNode = [&](int entry, int node) {
    std::vector<std::array<glm::dvec3, 16>> positions, tangents;
    switch (surface.nodeType(node)) {
      case SubdivSurface::NodeType::Regular:
        positions.resize(1), tangents.resize(1);
        surface.nodeGrid(node, positions[0], tangents[0]);
        t.faces[entry] = {sets, SubdivTables::kRegular};
        appendSets(positions, tangents);
        return;
      case SubdivSurface::NodeType::Irregular:
        surface.nodeSubPatches(node, kTableLevels, positions, tangents);
        t.faces[entry] = {sets, SubdivTables::kIrregular};
        appendSets(positions, tangents);
        return;
      case SubdivSurface::NodeType::Split: {
        const int first = static_cast<int>(t.faces.size());
        t.faces.resize(t.faces.size() + 4);
        t.faces[entry] = {first, SubdivTables::kSplit};
        for (int q = 0; q < 4; ++q) emitNode(first + q, surface.first_child(node) + q);
        return;
      }
    }
  };
  for (int f = 0; f < surface.patchCount(); ++f) {
    if (surface.rootNode(f) >= 0) {
      emitNode(f, surface.rootNode(f));
      continue;
    }
    std::vector<std::array<glm::dvec3, 16>> positions, tangents;
    if (surface.regular(f)) {
      positions = {surface.controlPoints(f, 0, 0)};
      tangents = {surface.controlPoints(f, 0, 0, true)};
      t.faces[f] = {sets, SubdivTables::kRegular};
    } else {
      surface.subPatches(f, kTableLevels, positions, tangents);
      t.faces[f] = {sets, SubdivTables::kIrregular};
    }
    appendSets(positions, tangents);
  }
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

FloatLimitPoint evaluateTables(const SubdivTables& tables, int face, float u, float v) {
  SubdivTables::FaceEntry e = tables.faces[face];
  // Down a split face's tree to the leaf whose square holds (u, v), in its own parameters.
  while (e.type == SubdivTables::kSplit) {
    const int a = u >= 0.5f ? 1 : 0, b = v >= 0.5f ? 1 : 0;
    u = 2.0f * u - float(a);
    v = 2.0f * v - float(b);
    e = tables.faces[e.first_set + (b == 0 ? a : 3 - a)];
  }
  int set = e.first_set;
  float s = u, t = v;
  if (e.type == SubdivTables::kIrregular) {
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
