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

// Additive sums (premultiplied emission and the sum of opacities) to a displayable pixel: each
// channel clamped to [0, 1] (rgb <= alpha before, so after too).
inline void clampAdditive(float* p) {
  for (int k = 0; k < 4; ++k) p[k] = std::clamp(p[k], 0.0f, 1.0f);
}

}  // namespace sortlast
