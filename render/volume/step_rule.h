#pragma once
// render.adaptive_step: how many lattice steps one sample of a block stands for. A block takes
// every m-th lattice sample (m = 2^j), each standing for the m steps around it that the block owns
// (render/volume/raycast_march.frag.glsl), with its opacity for their length. The error of one such
// sample is bounded by how much the transfer function varies over the values the segment can see:
// if every value along the segment and at its sample lies in [vmin, vmax], then
//   |tau(v(s)) - tau(v_sample)| <= osc(tau) and |c tau(v(s)) - c tau(v_sample)| <= osc(c tau)
// over [vmin, vmax] (osc = max - min), so the segment's optical depth, and its emission, are off by
// at most L osc, L = m delta its length. The rule takes the largest m with
//   m delta max(osc tau, osc r tau, osc g tau, osc b tau) <= tolerance,
// m <= 8 and m delta <= 2 voxels (an anchor then lies within the one-sample ghost layer of every
// brick owning part of its segment, so they all read the same value). A block whose range holds a
// steep ramp or a step of the function gets m = 1, as does a constant-free transfer function at a
// coarse spacing; a block over a flat part of it (any opacity, even opaque) gets the largest m.
// The osc is taken over the table entries the filtered lookup can blend for [vmin, vmax], so it
// bounds what the shader reads. The bound is per segment: a pixel's error is at most the sum over
// its coarse segments, each weighted by the transparency in front of it.
#include <vector>

#include "transfer/value_scale.h"

namespace sortlast {

class StepRule {
 public:
  // table: n entries (r, g, b, tau), tau per world unit, entry i at value lo + (hi - lo) i / (n - 1);
  // delta: the lattice step (world units); max_multiple: a power of two >= 1.
  // scale: transfer.scale, the domain the entries are evenly spaced in (lo, hi in data units).
  StepRule(const std::vector<float>& table, double lo, double hi, double delta, double tolerance,
           int max_multiple, ValueScale scale = {});
  // log2 m for a block whose segments see only values in [vmin, vmax].
  int level(float vmin, float vmax) const;

  // The largest power of two m <= 8 with m delta <= 2 min_spacing (at least 1).
  static int maxMultiple(double delta, double min_spacing);

 private:
  // The largest osc over the four channels of entries i0..i1 (sparse tables: O(1) per query).
  double oscillation(int i0, int i1) const;
  int n_;
  double lo_, hi_, delta_, tolerance_;
  ValueScale scale_;
  double slo_, shi_;  // lo, hi in the scale's domain
  int max_level_;
  std::vector<std::vector<float>> min_[4], max_[4];  // [channel][level][i]: over entries i .. i + 2^level - 1
};

}  // namespace sortlast
