#pragma once
// One brick's part of the reference's emission-absorption integral along one ray: what a rank
// holding only its bricks computes for the frame's accuracy estimate (session/frame_estimate.h).
// The same model and arithmetic as renderReference (reference/reference.h): the trilinear field of
// the original samples, the transfer function's colour and extinction in double, each step
// composited exactly with its midpoint value (T *= exp(-tau h)), gradient shading by central
// differences one voxel either side. A ray's segments in the bricks it crosses, composited front
// to back (by where each starts along the ray), give the whole ray's integral: the bricks are
// convex and meet face to face, and each holds one ghost layer of samples beyond its faces, so
// the field (and its gradient) inside a brick is the whole volume's.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "common/box.h"
#include "common/grid.h"
#include "transfer/shading.h"
#include "transfer/transfer_function.h"

namespace sortlast {

// A brick's samples seen as the whole volume's field over the brick.
struct BrickField {
  GridGeometry grid;      // the whole volume's
  IndexBox stored;        // the samples held: the brick's domain and its ghost layer
  const float* samples;   // stored.count() values, x fastest over `stored`
  // Trilinear at whole-volume index `u`, clamped to the whole grid (as WholeVolume::at) and to the
  // held samples (which only matters outside the brick's domain and ghost layer).
  double at(const glm::dvec3& u) const;
  glm::dvec3 gradient(const glm::dvec3& u) const;  // as WholeVolume::gradient
};

// Blocks of a brick's cells whose values all have zero opacity under a transfer function: the
// integrand is exactly zero there (trilinear values stay within their corners' range), so the
// segment integral jumps them. kCells cells a side, from the held samples' low corner.
struct EmptyBlocks {
  static constexpr int kCells = 4;
  glm::ivec3 count{0};
  std::vector<uint8_t> empty;  // x fastest; 1: no opacity anywhere in the block
  // Builds the map of `field` under `tf` (a NaN sample makes its blocks non-empty: the ray
  // caster's rules for missing samples are the integrator's).
  EmptyBlocks(const BrickField& field, const TransferFunction& tf);
  EmptyBlocks() = default;
};

struct SegmentIntegral {
  double rgb[3] = {0, 0, 0};  // premultiplied emission of the segment, seen from its start
  double transmit = 1.0;      // the segment's transmittance
};

// The integral over [t0, t1] of the ray o + t d (d unit) in steps of at most `step` world units
// (each the same length, the last too). Stops once the transmittance is below 1e-4 (what is left
// then moves no channel by more than 0.03/255). `flat`: flatGradient() of the transfer
// function's range. `empty` (built for the same field and function): steps in empty blocks are
// jumped, which changes nothing but the time.
SegmentIntegral integrateSegment(const BrickField& field, const TransferFunction& tf,
                                 const Shading& shading, double flat, const glm::dvec3& o,
                                 const glm::dvec3& d, double t0, double t1, double step,
                                 const EmptyBlocks* empty = nullptr);

}  // namespace sortlast
