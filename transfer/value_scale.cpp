#include "transfer/value_scale.h"

#include <cmath>
#include <limits>

namespace sortlast {

double ValueScale::apply(double v) const {
  switch (kind) {
    case ValueScaleKind::kLinear:
      return v;
    case ValueScaleKind::kLog:
      return v > 0.0 ? std::log10(v) : -std::numeric_limits<double>::infinity();
    case ValueScaleKind::kSymlog: {
      const double a = std::abs(v), w = linear_width;
      if (a <= w) return v * kSymlogC;
      return std::copysign(w * (kSymlogC + std::log10(a / w)), v);
    }
  }
  return v;
}

double ValueScale::inverse(double s) const {
  switch (kind) {
    case ValueScaleKind::kLinear:
      return s;
    case ValueScaleKind::kLog:
      return std::pow(10.0, s);
    case ValueScaleKind::kSymlog: {
      const double w = linear_width, a = std::abs(s);
      if (a <= w * kSymlogC) return s / kSymlogC;
      return std::copysign(w * std::pow(10.0, a / w - kSymlogC), s);
    }
  }
  return s;
}

}  // namespace sortlast
