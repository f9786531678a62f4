#include "render/particles/metaball_slices.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "io/particles.h"

namespace sortlast {

namespace {

// Margin on h when testing which voxels a particle reaches: the GPU computes lattice points and
// distances in float, so a point the CPU puts a hair outside a particle's reach must still find
// it in its list. 1% of h is far above float rounding (as kGridPad in render/particles/metaball_grid.h).
constexpr double kSlicePad = 0.01;

int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Calls f(voxel number) for every voxel of L that the ball (p, r) overlaps (closed boxes).
template <class F>
void forVoxelsOf(const SliceLattice& L, const glm::vec3& p, float r, F&& f) {
  const float edge = L.spacing * float(kSliceVoxelCells);
  glm::vec3 a = (p - r) / edge, b = (p + r) / edge;
  glm::ivec3 lo = glm::max(glm::ivec3(glm::floor(a)) - L.voxel_lo, glm::ivec3(0));
  glm::ivec3 hi = glm::min(glm::ivec3(glm::floor(b)) - L.voxel_lo, L.dims - 1);
  if (glm::any(glm::greaterThan(lo, hi))) return;
  const float r2 = r * r;
  auto gap = [&](int axis, int v) {
    // the voxel's faces as the shader places lattice points: float(k) * spacing
    float lo_face = float((L.voxel_lo[axis] + v) * kSliceVoxelCells) * L.spacing;
    float hi_face = float((L.voxel_lo[axis] + v + 1) * kSliceVoxelCells) * L.spacing;
    return std::max({lo_face - p[axis], 0.0f, p[axis] - hi_face});
  };
  for (int z = lo.z; z <= hi.z; ++z) {
    float dz = gap(2, z);
    for (int y = lo.y; y <= hi.y; ++y) {
      float dy = gap(1, y), dzy = dz * dz + dy * dy;
      if (dzy > r2) continue;
      size_t row = (size_t(z) * L.dims.y + y) * L.dims.x;
      for (int x = lo.x; x <= hi.x; ++x) {
        float dx = gap(0, x);
        if (dzy + dx * dx <= r2) f(row + size_t(x));
      }
    }
  }
}

}  // namespace

SliceLattice markSliceVoxels(const std::vector<glm::vec3>& particles, const Box3& clip, double h,
                             double spacing, double step, size_t max_entries,
                             const std::vector<float>* reach) {
  SliceLattice L;
  L.spacing = float(spacing);
  if (particles.empty()) return L;
  // The shader evaluates the field inside the clip box, up to one ray step before it (where a
  // bracket starts) and, for gradients, one spacing beyond that; interpolation spreads the field
  // up to one cell diagonal past where it is non-zero. The part of that box the field can reach,
  // then the cells that part touches, then their voxels.
  const Box3 served{clip.lo - (spacing + step), clip.hi + (spacing + step)};
  Box3 bound = fieldBoundInside(served, particles, h + std::sqrt(3.0) * spacing);
  if (glm::any(glm::greaterThanEqual(bound.lo, bound.hi))) return L;
  glm::dvec3 c_lo = glm::floor(bound.lo / spacing), c_hi = glm::floor(bound.hi / spacing);
  if (glm::any(glm::greaterThan(glm::max(glm::abs(c_lo), glm::abs(c_hi)), glm::dvec3(1 << 24))))
    throw std::length_error("the lattice index passes 2^24 (float exactness)");
  glm::ivec3 v_lo, v_hi;
  for (int a = 0; a < 3; ++a) {
    v_lo[a] = floorDiv(int(c_lo[a]), kSliceVoxelCells);
    v_hi[a] = floorDiv(int(c_hi[a]), kSliceVoxelCells);
  }
  L.voxel_lo = v_lo;
  L.dims = v_hi - v_lo + 1;
  if (double(L.dims.x) * L.dims.y * L.dims.z > double(max_entries))
    throw std::length_error("too many coarse voxels");
  const size_t n = L.voxelCount();
  const float r = float(h * (1.0 + kSlicePad));
  auto radius = [&](size_t i) { return reach ? float((*reach)[i] + h * kSlicePad) : r; };
  // 1. The bit voxelization: one pass over the particles.
  L.bits.assign((n + 63) / 64, 0);
  for (size_t i = 0; i < particles.size(); ++i)
    forVoxelsOf(L, particles[i], radius(i), [&](size_t v) { L.bits[v >> 6] |= uint64_t(1) << (v & 63); });
  return L;
}

void allocateSlices(SliceLattice& L, const std::vector<glm::vec3>& particles, double h,
                    size_t max_entries, const std::vector<float>* reach) {
  const size_t n = L.voxelCount();
  const float r = float(h * (1.0 + kSlicePad));
  auto radius = [&](size_t i) { return reach ? float((*reach)[i] + h * kSlicePad) : r; };
  // 2. Slots for the set bits, in voxel order.
  L.slot_of.assign(n, -1);
  for (size_t v = 0; v < n; ++v)
    if (L.occupied(v)) {
      L.slot_of[v] = int32_t(L.slot_voxel.size());
      const int x = int(v % size_t(L.dims.x)), y = int(v / size_t(L.dims.x) % size_t(L.dims.y)),
                z = int(v / (size_t(L.dims.x) * L.dims.y));
      L.slot_voxel.emplace_back(L.voxel_lo + glm::ivec3(x, y, z), 0);
    }
  if (L.slots() * size_t(kSliceSlotPoints) > max_entries)
    throw std::length_error("too many samples");
  // 3. Each slot's particles, by counting sort: particles in order, so every list ascends.
  L.offsets.assign(L.slots() + 1, 0);
  for (size_t i = 0; i < particles.size(); ++i)
    forVoxelsOf(L, particles[i], radius(i), [&](size_t v) { ++L.offsets[size_t(L.slot_of[v]) + 1]; });
  for (size_t s = 0; s < L.slots(); ++s) L.offsets[s + 1] += L.offsets[s];
  if (size_t(L.offsets.back()) * 4 > max_entries) throw std::length_error("too many list entries");
  L.items.resize(L.offsets.back());
  std::vector<uint32_t> cursor(L.offsets.begin(), L.offsets.end() - 1);
  for (size_t i = 0; i < particles.size(); ++i)
    forVoxelsOf(L, particles[i], radius(i),
                [&](size_t v) { L.items[cursor[size_t(L.slot_of[v])]++] = uint32_t(i); });
}

SliceLattice buildSliceLattice(const std::vector<glm::vec3>& particles, const Box3& clip, double h,
                               double spacing, double step, size_t max_entries,
                               const std::vector<float>* reach) {
  SliceLattice L = markSliceVoxels(particles, clip, h, spacing, step, max_entries, reach);
  if (L.voxelCount() > 0) allocateSlices(L, particles, h, max_entries, reach);
  return L;
}

}  // namespace sortlast
