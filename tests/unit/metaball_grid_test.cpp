// The particle grid of the metaball grid ray caster (render/particles/metaball_grid.h): every cell lists
// exactly the particles whose padded sphere of influence reaches it, in ascending order, so the
// field summed over a point's cell equals the field summed over all particles, in global order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "io/particles.h"
#include "render/particles/metaball_grid.h"

namespace sortlast {
namespace {

// A deterministic cloud in [-2, 2]^3 (integer hash, no std:: distributions).
std::vector<glm::vec3> cloud(int n) {
  std::vector<glm::vec3> p;
  uint32_t s = 12345;
  auto next = [&] {
    s = s * 1664525u + 1013904223u;
    return float(s >> 8) / float(1 << 24) * 4.0f - 2.0f;
  };
  for (int i = 0; i < n; ++i) {
    float x = next(), y = next(), z = next();
    p.push_back({x, y, z});
  }
  return p;
}

double cellDistance(const ParticleGrid& g, int x, int y, int z, const glm::vec3& p) {
  glm::dvec3 lo = glm::dvec3(g.lo) + glm::dvec3(x, y, z) * double(g.cell), hi = lo + double(g.cell);
  glm::dvec3 d = glm::max(glm::max(lo - glm::dvec3(p), glm::dvec3(0.0)), glm::dvec3(p) - hi);
  return glm::length(d);
}

TEST(MetaballGrid, CellsListExactlyTheParticlesInReachInOrder) {
  const double h = 0.5;
  std::vector<glm::vec3> p = cloud(500);
  Box3 bound{glm::dvec3(-1.5), glm::dvec3(1.7)};  // a brick's bound: ghosts lie outside it
  ParticleGrid g = buildParticleGrid(p, bound, h, h);
  ASSERT_EQ(g.dims, glm::ivec3(7));  // ceil((3.2 + 2 margin) / 0.5)
  ASSERT_EQ(g.offsets.size(), g.cellCount() + 1);
  ASSERT_EQ(g.offsets.back(), g.items.size());
  const double r = h * (1.0 + kGridPad);
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x) {
        size_t c = (size_t(z) * g.dims.y + y) * g.dims.x + x;
        std::vector<uint32_t> want;
        for (size_t i = 0; i < p.size(); ++i)
          if (cellDistance(g, x, y, z, p[i]) <= r - 1e-6) want.push_back(uint32_t(i));
        std::vector<uint32_t> got(g.items.begin() + g.offsets[c], g.items.begin() + g.offsets[c + 1]);
        ASSERT_TRUE(std::is_sorted(got.begin(), got.end())) << "cell " << c;
        // Everything in reach is listed; anything else listed lies within float rounding of r.
        ASSERT_TRUE(std::includes(got.begin(), got.end(), want.begin(), want.end())) << "cell " << c;
        for (uint32_t i : got) ASSERT_LE(cellDistance(g, x, y, z, p[i]), r + 1e-5) << "cell " << c;
      }
}

TEST(MetaballGrid, FieldOverACellEqualsTheFullSumBitForBit) {
  const double h = 0.4;
  std::vector<glm::vec3> p = cloud(2000);
  Box3 bound{glm::dvec3(-2.0 - h), glm::dvec3(2.0 + h)};
  ParticleGrid g = buildParticleGrid(p, bound, h, h);
  std::vector<glm::vec3> points = cloud(300);
  for (const glm::vec3& x : points) {
    float all = 0.0f, cell = 0.0f;
    auto P = [&](const glm::vec3& c) {
      float q = std::max(1.0f - glm::length(x - c) / float(h), 0.0f);
      return q * q;
    };
    for (const glm::vec3& c : p) all += P(c);
    glm::ivec3 k = glm::clamp(glm::ivec3(glm::floor((x - g.lo) / g.cell)), glm::ivec3(0), g.dims - 1);
    size_t c = (size_t(k.z) * g.dims.y + k.y) * g.dims.x + k.x;
    for (uint32_t j = g.offsets[c]; j < g.offsets[c + 1]; ++j) cell += P(p[g.items[j]]);
    ASSERT_EQ(all, cell);
  }
}

TEST(MetaballGrid, CoarsensToStayUnderTheCellBudget) {
  std::vector<glm::vec3> p = {{0, 0, 0}, {10, 10, 10}};
  ParticleGrid g = buildParticleGrid(p, Box3{glm::dvec3(-1), glm::dvec3(11)}, 0.1, 0.1, 1000);
  EXPECT_LE(g.cellCount(), 1000u);
  EXPECT_GT(g.cell, 0.1f);
  // Each particle still reaches the cell it sits in.
  EXPECT_EQ(g.offsets.back(), g.items.size());
  EXPECT_GE(g.items.size(), 2u);
}

TEST(MetaballGrid, EmptyAndOrderedInput) {
  ParticleGrid g = buildParticleGrid({}, Box3{glm::dvec3(0), glm::dvec3(1)}, 0.5, 0.5);
  EXPECT_EQ(g.items.size(), 0u);
  EXPECT_EQ(g.offsets.size(), g.cellCount() + 1);
}

}  // namespace
}  // namespace sortlast
