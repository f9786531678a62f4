#pragma once
// The colour of a projected value (render.blend: mip, minip, average): the transfer function's
// colour c(v) and opacity a(v) (per unit_length, as transfer.opacity gives it) at the value,
// premultiplied: (c(v) a(v), a(v)). One definition for the GL session's final frame and the CPU
// reference (docs/volumes.md). Additive pixels are already colour: clampAdditive only bounds them.
#include <algorithm>
#include <array>

#include "transfer/transfer_function.h"

namespace sortlast {

inline std::array<double, 4> projectedColour(const TransferFunction& tf, double v) {
  const std::array<double, 3> c = tf.colour(v);
  const double a = std::clamp(tf.opacity(v), 0.0, 1.0);
  return {c[0] * a, c[1] * a, c[2] * a, a};
}

// A projection's colour `c` (premultiplied) in front of an opaque layer of colour `layer`: the
// pixel of a projection bounded by particles or surfaces (its samples all lie in front of them).
inline std::array<double, 4> overOpaque(const std::array<double, 4>& c, const std::array<double, 3>& layer) {
  const double t = 1.0 - c[3];
  return {c[0] + t * layer[0], c[1] + t * layer[1], c[2] + t * layer[2], 1.0};
}

// Additive sums (premultiplied emission and the sum of opacities) to a displayable pixel: each
// channel clamped to [0, 1] (rgb <= alpha before, so after too).
inline void clampAdditive(float* p) {
  for (int k = 0; k < 4; ++k) p[k] = std::clamp(p[k], 0.0f, 1.0f);
}

}  // namespace sortlast
