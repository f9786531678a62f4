// The lattice of the slices method (render/particles/metaball_slices.h): the voxels are global (the same
// indices in every brick), a voxel has a slot exactly when some particle reaches its box (up to
// the 1% pad), and each slot lists every particle that reaches it, ascending, so a lattice point
// sums the same particles in the same order in every brick that holds it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "render/particles/metaball_slices.h"

namespace sortlast {
namespace {

std::vector<glm::vec3> sliceCloud(int n) {  // deterministic, in [-2, 2]^3
  std::vector<glm::vec3> p;
  uint32_t s = 777;
  auto next = [&] {
    s = s * 1664525u + 1013904223u;
    return float(s >> 8) / float(1 << 24) * 4.0f - 2.0f;
  };
  for (int i = 0; i < n; ++i) p.push_back({next(), next(), next()});
  return p;
}

// Distance from p to global voxel v's closed box.
double gap(const glm::vec3& p, glm::ivec3 v, double edge) {
  glm::dvec3 lo = glm::dvec3(v) * edge, hi = lo + edge, q(p);
  glm::dvec3 d = glm::max(glm::max(lo - q, q - hi), glm::dvec3(0.0));
  return glm::length(d);
}

TEST(MetaballSlices, SlotsAndListsMatchBruteForce) {
  const double h = 0.5, spacing = 0.125, step = h / 8;
  std::vector<glm::vec3> all = sliceCloud(300);
  const Box3 clip{{-1.0, -0.5, -1.2}, {0.7, 1.1, 0.3}};
  SliceLattice L = buildSliceLattice(all, clip, h, spacing, step);
  ASSERT_GT(L.slots(), 0u);
  const double edge = spacing * kSliceVoxelCells;
  // The voxels cover the clip box grown by spacing + step (where the shader reads).
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(L.voxel_lo[a] * edge, clip.lo[a] - spacing - step + 1e-9);
    EXPECT_GE((L.voxel_lo[a] + L.dims[a]) * edge, clip.hi[a] + spacing + step - 1e-9);
  }
  size_t slot = 0;
  for (int z = 0; z < L.dims.z; ++z)
    for (int y = 0; y < L.dims.y; ++y)
      for (int x = 0; x < L.dims.x; ++x) {
        const size_t v = (size_t(z) * L.dims.y + y) * L.dims.x + x;
        const glm::ivec3 g = L.voxel_lo + glm::ivec3(x, y, z);
        std::vector<uint32_t> must, may;  // within h; within the padded reach
        for (size_t i = 0; i < all.size(); ++i) {
          double d = gap(all[i], g, edge);
          if (d <= h * 0.999) must.push_back(uint32_t(i));
          if (d <= h * 1.011) may.push_back(uint32_t(i));
        }
        if (!L.occupied(v)) {
          EXPECT_TRUE(must.empty()) << "voxel " << v << " reached but not marked";
          EXPECT_EQ(L.slot_of[v], -1);
          continue;
        }
        ASSERT_EQ(L.slot_of[v], int32_t(slot)) << "slots in voxel order";
        EXPECT_EQ(L.slot_voxel[slot].x, g.x);
        EXPECT_EQ(L.slot_voxel[slot].y, g.y);
        EXPECT_EQ(L.slot_voxel[slot].z, g.z);
        std::vector<uint32_t> list(L.items.begin() + L.offsets[slot], L.items.begin() + L.offsets[slot + 1]);
        EXPECT_TRUE(std::is_sorted(list.begin(), list.end()));
        for (uint32_t i : must) EXPECT_TRUE(std::binary_search(list.begin(), list.end(), i));
        for (uint32_t i : list) EXPECT_TRUE(std::binary_search(may.begin(), may.end(), i));
        ++slot;
      }
  EXPECT_EQ(slot, L.slots());
}

TEST(MetaballSlices, VoxelsAreGlobal) {
  // Two bricks sharing the face x = 0: a voxel both hold has the same global index and, given the
  // same particles near it, the same list.
  const double h = 0.5, spacing = 0.1, step = h / 8;
  std::vector<glm::vec3> all = sliceCloud(200);
  SliceLattice a = buildSliceLattice(all, Box3{{-2, -2, -2}, {0, 2, 2}}, h, spacing, step);
  SliceLattice b = buildSliceLattice(all, Box3{{0, -2, -2}, {2, 2, 2}}, h, spacing, step);
  int shared = 0;
  for (size_t sa = 0; sa < a.slots(); ++sa)
    for (size_t sb = 0; sb < b.slots(); ++sb) {
      if (glm::ivec3(a.slot_voxel[sa]) != glm::ivec3(b.slot_voxel[sb])) continue;
      ++shared;
      std::vector<uint32_t> la(a.items.begin() + a.offsets[sa], a.items.begin() + a.offsets[sa + 1]);
      std::vector<uint32_t> lb(b.items.begin() + b.offsets[sb], b.items.begin() + b.offsets[sb + 1]);
      EXPECT_EQ(la, lb);
    }
  EXPECT_GT(shared, 0);
}

TEST(MetaballSlices, NoParticlesNoVoxels) {
  SliceLattice L = buildSliceLattice({}, Box3{{0, 0, 0}, {1, 1, 1}}, 0.5, 0.1, 0.05);
  EXPECT_EQ(L.slots(), 0u);
  EXPECT_EQ(L.voxelCount(), 0u);
}

TEST(MetaballSlices, TooManySamplesThrows) {
  EXPECT_THROW(buildSliceLattice(sliceCloud(50), Box3{{-2, -2, -2}, {2, 2, 2}}, 0.5, 0.01, 0.05, 1000),
               std::length_error);
}

}  // namespace
}  // namespace sortlast
