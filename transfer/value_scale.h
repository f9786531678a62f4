#pragma once
// transfer.scale: the domain the transfer function is laid out in. The range [lo, hi] is in data
// units; a value's place in it, x in [0, 1], is (s(v) - s(lo)) / (s(hi) - s(lo)) with s:
//   linear: s(v) = v
//   log:    s(v) = log10(v); v <= 0 maps below the range (x = 0), and the range needs lo > 0
//   symlog: matplotlib's SymLogNorm (base 10, linscale 1) with linthresh w = transfer.linear_width:
//           s(v) = v c for |v| <= w, sign(v) w (c + log10(|v| / w)) beyond, c = 1 / (1 - 1/10),
//           linear within +-w of zero and logarithmic beyond, continuous and increasing.
// The transfer function's control points are at x (as a matplotlib colour map under a norm), so
// its table is laid out evenly in s. Every user (the GLSL classifiers, pre-integration, block
// classification, the reference, the legend) goes through this one definition; the GLSL copy is
// render/volume/value_scale.glsl.
#include <array>
#include <string>

#include "common/enum_names.h"

namespace sortlast {

enum class ValueScaleKind { kLinear, kLog, kSymlog };
template <>
inline constexpr std::array kEnumNames<ValueScaleKind>{"linear", "log", "symlog"};

struct ValueScale {
  ValueScaleKind kind = ValueScaleKind::kLinear;
  double linear_width = 1.0;  // symlog's w (data units, > 0)

  // SymLogNorm's c = linscale / (1 - 1 / base), linscale 1, base 10.
  static constexpr double kSymlogC = 1.0 / (1.0 - 0.1);

  // s(v); log of v <= 0 is -infinity.
  double apply(double v) const;
  // The inverse of s (for tick values and the legend).
  double inverse(double s) const;
  bool operator==(const ValueScale& o) const {
    return kind == o.kind && (kind != ValueScaleKind::kSymlog || linear_width == o.linear_width);
  }
};

}  // namespace sortlast
