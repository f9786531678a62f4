#pragma once
// Where the slices method (render/particles/metaball_slices_renderer.h) keeps its density samples: the
// third paper's dynamic slices (../shared/PAPERS.md §3), pure CPU so it is unit-tested without GL.
//
// One global lattice of points k * spacing (k integer, world origin), the same for every brick
// and rank, so a point two bricks share gets the same sum in both (and the image is seamless and
// rank-invariant). It is cut into coarse voxels of kSliceVoxelCells cells per edge, also global.
// A brick marks, one bit per voxel, the voxels some particle's sphere of influence reaches
// (the paper's bit voxelization) and gives only those a slot of (kSliceVoxelCells + 1)^3 samples
// (the paper's dynamic allocation; the extra layer repeats the next voxel's first points, so a
// trilinear lookup never leaves its slot). Each slot lists the particles that reach it, in the
// brick's (global) order: the GPU sums them per point in that order
// (render/particles/metaball_slices_splat.comp.glsl).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "common/box.h"

namespace sortlast {

// Lattice cells per coarse voxel edge. At the default spacing h/4 a voxel is h wide: a slot's list
// holds the particles within h of an h-cube. Measured with build/bench/bench_metaball_slices (65,536
// splash particles, one brick, busy 2-core machine), a brick's whole work (lattice, upload,
// splat) and its samples: 2 cells 0.93 s, 23.8 MiB; 4 cells 0.54 s, 17.8 MiB; 8 cells 0.71 s,
// 19.7 MiB (with a point per invocation, before the splat summed columns: 2.87 / 1.35-1.95 /
// 2.51 s). Smaller voxels fit the particles closer but list each particle in more slots; larger
// ones make every point of a slot walk a longer list.
inline constexpr int kSliceVoxelCells = 4;
inline constexpr int kSliceSlotSide = kSliceVoxelCells + 1;
inline constexpr int kSliceSlotPoints = kSliceSlotSide * kSliceSlotSide * kSliceSlotSide;

struct SliceLattice {
  float spacing = 1.0f;                // lattice spacing (world units)
  glm::ivec3 voxel_lo{0};              // global index of the brick's coarse voxel (0, 0, 0)
  glm::ivec3 dims{0};                  // coarse voxels per axis
  std::vector<uint64_t> bits;          // 1 bit per coarse voxel: some particle reaches it
  std::vector<int32_t> slot_of;        // per coarse voxel (x fastest): its slot, -1 if empty
  std::vector<glm::ivec4> slot_voxel;  // per slot: its global voxel index (xyz, w unused)
  std::vector<uint32_t> offsets;       // slots + 1: slot i lists items[offsets[i], offsets[i+1])
  std::vector<uint32_t> items;         // particle indices, ascending within each slot
  size_t voxelCount() const { return size_t(dims.x) * dims.y * dims.z; }
  size_t slots() const { return slot_voxel.size(); }
  bool occupied(size_t voxel) const { return (bits[voxel >> 6] >> (voxel & 63)) & 1u; }
};

// The coarse voxels whose lattice cells the shader can interpolate in for `clip`'s brick (points in
// `clip`, up to one ray step `step` before it, and, for gradients, one spacing beyond), as far as
// `particles` (the brick's own and its ghosts, ParticleDesc::ghostMargin) can make the interpolated
// field non-zero there; then the bits, slots and lists. `spacing` in world units. Throws
// std::length_error when the voxels, the samples or the lists (4 words an entry) would pass
// `max_entries` 4-byte words, what one GPU buffer holds (the caller turns it into an error naming
// particles.slice_spacing).
// `reach` (optional, one per particle; anisotropic kernels: the longest semi-axis): each
// particle's own radius of influence instead of h, which must then be at least the largest.
SliceLattice buildSliceLattice(const std::vector<glm::vec3>& particles, const Box3& clip, double h,
                               double spacing, double step, size_t max_entries = size_t(1) << 28,
                               const std::vector<float>* reach = nullptr);

// The two steps of buildSliceLattice: the voxels and their bits; then the slots and lists.
SliceLattice markSliceVoxels(const std::vector<glm::vec3>& particles, const Box3& clip, double h,
                             double spacing, double step, size_t max_entries = size_t(1) << 28,
                             const std::vector<float>* reach = nullptr);
void allocateSlices(SliceLattice& L, const std::vector<glm::vec3>& particles, double h,
                    size_t max_entries = size_t(1) << 28, const std::vector<float>* reach = nullptr);

}  // namespace sortlast
