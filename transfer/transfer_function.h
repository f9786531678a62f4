#pragma once
// Transfer function: colour and opacity as piecewise-linear functions of the data value, given by
// control points over the normalised range [0, 1] (0 = range.lo, 1 = range.hi; values outside the
// range clamp to its ends).
//
// Opacity a(v) is the opacity of a slab of thickness `unit_length` (world units). A sample that
// stands for a ray segment of length ds gets a = 1 - (1 - a(v))^(ds / unit_length), which is the
// slice-spacing correction; as ds -> 0 this is the emission-absorption model with extinction
// tau(v) = -ln(1 - a(v)) / unit_length and emitted colour c(v) * tau(v). Both the GL renderer and
// the reference integrator use that one model.
#include <array>
#include <string>
#include <vector>

namespace sortlast {

struct TfPoint {
  double value;  // in [0, 1] of the data range
  double r, g, b, a;
};

class TransferFunction {
 public:
  TransferFunction() = default;
  TransferFunction(std::vector<TfPoint> points, double range_lo, double range_hi,
                   double unit_length);

  static std::vector<TfPoint> preset(const std::string& name);  // throws InputError if unknown

  double normalise(double v) const;               // data value -> [0, 1] (clamped)
  std::array<double, 3> colour(double v) const;   // of the raw data value
  double opacity(double v) const;                 // per unit_length, of the raw data value
  double extinction(double v) const;              // tau, per world unit

  // Largest opacity over raw data values in [lo, hi]: zero means a brick whose samples all lie in
  // [lo, hi] is invisible.
  double maxOpacity(double lo, double hi) const;

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
  const std::vector<TfPoint>& points() const { return pts_; }

  // Largest extinction any value can have: opacity is capped just below 1 so tau stays finite.
  static constexpr double kMaxOpacity = 0.999999;

 private:
  std::array<double, 4> evalNormalised(double x) const;
  std::vector<TfPoint> pts_;
  double lo_ = 0.0, hi_ = 1.0, unit_ = 1.0;
};

}  // namespace sortlast
