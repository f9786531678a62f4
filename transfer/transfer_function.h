#pragma once
// Transfer function: colour and opacity as piecewise-linear functions of the data value, given by
// control points over the normalised range [0, 1] (0 = range.lo, 1 = range.hi; values outside the
// range clamp to its ends). The range is in data units; a value's normalised place in it is
// measured in the domain of its scale (transfer/value_scale.h: linear, log or symlog), so under
// log the points and the table are evenly spaced in log10 of the value.
//
// Opacity a(v) is the opacity of a slab of thickness `unit_length` (world units). A sample that
// stands for a ray segment of length ds gets a = 1 - (1 - a(v))^(ds / unit_length), which is the
// slice-spacing correction; as ds -> 0 this is the emission-absorption model with extinction
// tau(v) = -ln(1 - a(v)) / unit_length and emitted colour c(v) * tau(v). Both the GL renderer and
// the reference integrator use that one model.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "transfer/value_scale.h"

namespace sortlast {

struct TfPoint {
  double value;  // in [0, 1] of the data range
  double r, g, b, a;
};

class TransferFunction {
 public:
  TransferFunction() = default;
  // Under log scale the range needs lo > 0 (throws InputError naming transfer.range).
  TransferFunction(std::vector<TfPoint> points, double range_lo, double range_hi,
                   double unit_length, ValueScale scale = {});

  static std::vector<TfPoint> preset(const std::string& name);  // throws InputError if unknown

  double normalise(double v) const;               // data value -> [0, 1] (clamped), in the scale
  double denormalise(double x) const;             // [0, 1] -> data value (the scale's inverse)
  std::array<double, 3> colour(double v) const;   // of the raw data value
  double opacity(double v) const;                 // per unit_length, of the raw data value
  double extinction(double v) const;              // tau, per world unit
  // (r, g, b, opacity) of the raw data value: colour() and opacity() in one lookup.
  std::array<double, 4> at(double v) const { return evalNormalised(normalise(v)); }
  // tau, per world unit, of an opacity per unit_length (capped at kMaxOpacity). Inline: the
  // references and the frame's estimate call it two or three times a step.
  double extinctionOfOpacity(double a) const { return -std::log1p(-std::min(a, kMaxOpacity)) / unit_; }

  // Largest opacity over raw data values in [lo, hi]: zero means a brick whose samples all lie in
  // [lo, hi] is invisible.
  double maxOpacity(double lo, double hi) const;
  // The function at a normalised place x in [0, 1]: (r, g, b, opacity).
  std::array<double, 4> atNormalised(double x) const { return evalNormalised(x); }
  // (a, b) with normalised x = s(v) a + b, s the scale (the GLSL classifiers' u_value_map).
  std::array<double, 2> scaledValueMap() const;

  // Lookup table of n entries (r, g, b, tau); entry i is the value at normalised i / (n - 1), so
  // a linearly filtered texture addressed at (x * (n - 1) + 0.5) / n reproduces the table's ends.
  std::vector<float> bakeTable(int n) const;

  // Whether values in [vmin, vmax], looked up in the linearly filtered n-entry table, can read an
  // entry with non-zero opacity: a value at table coordinate x blends entries floor(x) and
  // floor(x) + 1 (weight frac(x) on the second), so the span reads entries floor(x(vmin)) ..
  // ceil(x(vmax)) and nothing else. False means a block of such values is empty, exactly.
  bool tableSpanVisible(int n, double vmin, double vmax) const;

  double rangeLo() const { return lo_; }
  double rangeHi() const { return hi_; }
  double unitLength() const { return unit_; }
  const ValueScale& scale() const { return scale_; }
  const std::vector<TfPoint>& points() const { return pts_; }
  // The raw data values where colour or opacity has a kink (each point's value and the range's
  // ends, where the clamp begins; under symlog also +-linear_width inside the range, where the
  // scale changes slope), increasing: a step of an integrator whose values cross one holds a
  // kink of its integrand, which the midpoint rule treats to first order only.
  const std::vector<double>& kinkValues() const { return kinks_; }
  // Those of them where opacity has its kink (a colour map's points are kinks of colour only).
  const std::vector<double>& opacityKinkValues() const { return opacity_kinks_; }
  // Everything the function's values depend on (range, unit length, scale, each point), appended
  // to `key`: for caches of what was computed from it (a probe's step, the estimate's block maps).
  void appendKey(std::vector<double>& key) const;

  // Largest extinction any value can have: opacity is capped just below 1 so tau stays finite.
  static constexpr double kMaxOpacity = 0.999999;

 private:
  std::array<double, 4> evalNormalised(double x) const;
  double maxOpacityNormalised(double xl, double xh) const;
  std::vector<TfPoint> pts_;
  double lo_ = 0.0, hi_ = 1.0, unit_ = 1.0;
  ValueScale scale_;
  double slo_ = 0.0, shi_ = 1.0;  // the range's ends in the scale's domain
  std::vector<double> kinks_;
  std::vector<double> opacity_kinks_;
};

}  // namespace sortlast
