#pragma once
// One brick's part of the reference's emission-absorption integral along one ray: what a rank
// holding only its bricks computes for the frame's accuracy estimate (session/frame_estimate.h).
// The same model as renderReference (reference/reference.h): the trilinear field of the original
// samples, the transfer function's colour and extinction in double, gradient shading by central
// differences one voxel either side. Without block maps, also its arithmetic: each step
// composited exactly (T *= exp(-tau h)) with its middle's colour and Simpson's optical depth, cut
// where its end values straddle a kink of the transfer function. With them (the estimate's way),
// the same integral to a tolerance, cell by cell (integrateSegment below). A ray's segments in the bricks it crosses, composited front
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

// Per block of a brick's cells (kCells a side, from the held samples' low corner): whether its
// values all have zero opacity (the integrand is exactly zero there: trilinear values stay within
// their corners' range, so the segment integral jumps the block), and how many reference steps
// one midpoint sample may stand for there. The second follows the ray caster's adaptive-step bound
// (render/volume/step_rule.h): over the block's values [vmin, vmax] the extinction tau and the
// emission c tau vary by at most osc, so a sample standing for a length L is off by at most L osc
// in optical depth and emission; the largest power of two m <= kMaxMultiple with m step osc <=
// kTolerance is taken (1 with shading: the colour follows the gradient, not the value).
struct EmptyBlocks {
  static constexpr int kCells = 4;
  static constexpr int kMaxMultiple = 16;
  static constexpr double kTolerance = 2e-4;
  glm::ivec3 count{0};
  std::vector<uint8_t> empty;     // x fastest; 1: no opacity anywhere in the block
  std::vector<uint8_t> multiple;  // x fastest; steps one sample stands for
  // The maps of `field` under `tf` for steps of `step` world units (a NaN sample makes its blocks
  // non-empty and m 1: the ray caster's rules for missing samples are the integrator's).
  EmptyBlocks(const BrickField& field, const TransferFunction& tf, double step = 0.0, bool shading = true);
  EmptyBlocks() = default;
};

struct SegmentIntegral {
  double rgb[3] = {0, 0, 0};  // premultiplied emission of the segment, seen from its start
  double transmit = 1.0;      // the segment's transmittance
};

// The integral over [t0, t1] of the ray o + t d (d unit) in steps of at most `step` world units
// (each the same length, the last too). Stops once the transmittance is below `stop_transmit`
// (1e-4: what is left then moves no channel by more than 0.03/255). `flat`: flatGradient() of the transfer
// function's range. `empty` (built for the same field, function and step): empty blocks are
// jumped (which changes nothing but the time) and, under a linear scale, each other block is
// integrated cell by cell instead of in steps: each cell's crossing is cut where the field (a
// cubic along the ray inside a cell) turns and where it meets a kink of opacity, so that on each
// piece extinction is smooth, and each piece is integrated by adaptive Simpson (optical depth
// and emission, the two halves' result kept where it agrees with the whole's within 1e-5 per
// voxel of the piece's length, over the transmittance in front of it; colour's own kinks are
// left to the halving).
// Shaded too: the gradient's taps lie in the neighbouring cells at the same place, so it is
// smooth inside a crossing. Against a march 32 times finer, the unit tests' cell march is 6e-6
// to 1.3e-5 off (the reference's 1/16-voxel step: 8e-5 to 1.3e-3) and takes 2-6x fewer
// evaluations than the steps it replaced (results/accuracy/estimate_cost.md). Any scale: log and
// symlog are smooth between the kinks (symlog's own at +-linear_width among them). Where the
// field clamps (outside the grid or the held samples), steps of the block's `multiple` of `step`.
SegmentIntegral integrateSegment(const BrickField& field, const TransferFunction& tf,
                                 const Shading& shading, double flat, const glm::dvec3& o,
                                 const glm::dvec3& d, double t0, double t1, double step,
                                 const EmptyBlocks* empty = nullptr, double stop_transmit = 1e-4);

}  // namespace sortlast
