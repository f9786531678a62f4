#include "transfer/transfer_function.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace sortlast {

TransferFunction::TransferFunction(std::vector<TfPoint> points, double range_lo, double range_hi,
                                   double unit_length, ValueScale scale)
    : pts_(std::move(points)), lo_(range_lo), hi_(range_hi), unit_(unit_length), scale_(scale) {
  if (pts_.empty()) throw InputError("transfer.points: needs at least one control point");
  for (size_t i = 0; i < pts_.size(); ++i) {
    const TfPoint& p = pts_[i];
    for (double c : {p.value, p.r, p.g, p.b, p.a}) {
      if (!std::isfinite(c) || c < 0.0 || c > 1.0)
        throw InputError("transfer.points[" + std::to_string(i) +
                         "]: every entry (value, r, g, b, a) must lie in [0, 1]");
    }
    if (i > 0 && p.value < pts_[i - 1].value)
      throw InputError("transfer.points: values must be in increasing order");
  }
  if (!(range_hi > range_lo) || !std::isfinite(range_lo) || !std::isfinite(range_hi))
    throw InputError("transfer.range: needs lo < hi (got " + std::to_string(range_lo) + ", " +
                     std::to_string(range_hi) + ")");
  if (!(unit_length > 0.0)) throw InputError("transfer.unit_length: must be > 0");
  if (scale_.kind == ValueScaleKind::kLog && !(range_lo > 0.0))
    throw InputError("transfer.range: [" + std::to_string(range_lo) + ", " + std::to_string(range_hi) +
                     "] has an end <= 0, which transfer.scale: log cannot map (use symlog)");
  if (scale_.kind == ValueScaleKind::kSymlog && !(scale_.linear_width > 0.0))
    throw InputError("transfer.linear_width: must be > 0");
  slo_ = scale_.apply(lo_);
  shi_ = scale_.apply(hi_);
  // Kinks: the places in [0, 1] where a channel's slope changes (the slope is 0 outside [0, 1],
  // where values clamp), as raw values. Collinear points are no kink.
  auto slopeAt = [&](double x, bool right) {  // the slope of each channel just right/left of x
    std::array<double, 4> k{0, 0, 0, 0};
    if ((right && x >= 1.0) || (!right && x <= 0.0)) return k;
    const double e = 1e-9, a = right ? x : x - e, b = right ? x + e : x;
    const std::array<double, 4> fa = evalNormalised(a), fb = evalNormalised(b);
    for (int c = 0; c < 4; ++c) k[c] = (fb[c] - fa[c]) / e;
    return k;
  };
  std::vector<double> places{0.0, 1.0};
  for (const TfPoint& p : pts_) places.push_back(p.value);
  std::sort(places.begin(), places.end());
  places.erase(std::unique(places.begin(), places.end()), places.end());
  for (double x : places) {
    const std::array<double, 4> l = slopeAt(x, false), r = slopeAt(x, true);
    auto bends = [&](int c) { return std::abs(l[c] - r[c]) > 1e-6 * (1.0 + std::abs(l[c]) + std::abs(r[c])); };
    if (bends(0) || bends(1) || bends(2) || bends(3)) kinks_.push_back(denormalise(x));
    if (bends(3)) opacity_kinks_.push_back(denormalise(x));
  }
  // symlog's own kinks: its s(v) changes slope at +-w (linear inside, logarithmic beyond), so
  // every channel that is not flat there does too as a function of the raw value.
  if (scale_.kind == ValueScaleKind::kSymlog) {
    for (std::vector<double>* k : {&kinks_, &opacity_kinks_}) {
      for (double w : {-scale_.linear_width, scale_.linear_width})
        if (w > lo_ && w < hi_) k->push_back(w);
      std::sort(k->begin(), k->end());
      k->erase(std::unique(k->begin(), k->end()), k->end());
    }
  }
}

std::vector<TfPoint> TransferFunction::preset(const std::string& name) {
  if (name == "ramp")  // the paper's protocol: opacity = voxel value, grey
    return {{0.0, 0.0, 0.0, 0.0, 0.0}, {1.0, 1.0, 1.0, 1.0, 1.0}};
  if (name == "default")  // soft blue haze, orange shells, white cores
    return {{0.00, 0.0, 0.0, 0.0, 0.0},  {0.15, 0.1, 0.2, 0.8, 0.0},  {0.30, 0.2, 0.4, 1.0, 0.03},
            {0.50, 1.0, 0.5, 0.1, 0.15}, {0.70, 1.0, 0.8, 0.3, 0.35}, {1.00, 1.0, 1.0, 1.0, 0.8}};
  if (name == "sharp")  // a narrow opaque band: edges that show every seam
    return {{0.0, 0, 0, 0, 0}, {0.45, 0.2, 0.5, 1.0, 0.0}, {0.5, 1.0, 0.9, 0.6, 0.9},
            {0.55, 1.0, 0.3, 0.1, 0.0}, {1.0, 1.0, 1.0, 1.0, 0.3}};
  throw InputError("transfer.preset: unknown preset '" + name + "' (known: ramp, default, sharp)");
}

double TransferFunction::normalise(double v) const {
  if (scale_.kind == ValueScaleKind::kLinear) return std::clamp((v - lo_) / (hi_ - lo_), 0.0, 1.0);
  if (scale_.kind == ValueScaleKind::kLog && !(v > 0.0)) return 0.0;  // below the range
  return std::clamp((scale_.apply(v) - slo_) / (shi_ - slo_), 0.0, 1.0);
}

double TransferFunction::denormalise(double x) const {
  if (scale_.kind == ValueScaleKind::kLinear) return lo_ + x * (hi_ - lo_);
  return scale_.inverse(slo_ + x * (shi_ - slo_));
}

std::array<double, 2> TransferFunction::scaledValueMap() const {
  const double d = shi_ - slo_;
  return {1.0 / d, -slo_ / d};
}

std::array<double, 4> TransferFunction::evalNormalised(double x) const {
  if (x <= pts_.front().value) return {pts_.front().r, pts_.front().g, pts_.front().b, pts_.front().a};
  if (x >= pts_.back().value) return {pts_.back().r, pts_.back().g, pts_.back().b, pts_.back().a};
  auto it = std::upper_bound(pts_.begin(), pts_.end(), x,
                             [](double v, const TfPoint& p) { return v < p.value; });
  const TfPoint& b = *it;
  const TfPoint& a = *(it - 1);
  double f = (b.value > a.value) ? (x - a.value) / (b.value - a.value) : 1.0;
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b), a.a + f * (b.a - a.a)};
}

std::array<double, 3> TransferFunction::colour(double v) const {
  auto e = evalNormalised(normalise(v));
  return {e[0], e[1], e[2]};
}

double TransferFunction::opacity(double v) const { return evalNormalised(normalise(v))[3]; }

double TransferFunction::extinction(double v) const { return extinctionOfOpacity(opacity(v)); }


double TransferFunction::maxOpacity(double lo, double hi) const {
  return maxOpacityNormalised(normalise(lo), normalise(hi));
}

double TransferFunction::maxOpacityNormalised(double xl, double xh) const {
  double m = std::max(evalNormalised(xl)[3], evalNormalised(xh)[3]);
  for (const TfPoint& p : pts_)
    if (p.value > xl && p.value < xh) m = std::max(m, p.a);
  return m;
}

std::vector<float> TransferFunction::bakeTable(int n) const {
  std::vector<float> t(4 * size_t(n));
  for (int i = 0; i < n; ++i) {
    auto e = evalNormalised(double(i) / (n - 1));
    t[4 * i + 0] = float(e[0]);
    t[4 * i + 1] = float(e[1]);
    t[4 * i + 2] = float(e[2]);
    t[4 * i + 3] = float(-std::log1p(-std::min(e[3], kMaxOpacity)) / unit_);
  }
  return t;
}

void TransferFunction::appendKey(std::vector<double>& key) const {
  key.insert(key.end(), {lo_, hi_, unit_, double(scale_.kind), scale_.linear_width});
  for (const TfPoint& p : pts_) key.insert(key.end(), {p.value, p.r, p.g, p.b, p.a});
}

bool TransferFunction::tableSpanVisible(int n, double vmin, double vmax) const {
  // A value on an entry reads that entry alone, so a block of the volume's lowest value under a
  // ramp is empty (a pad of one entry either side, the rule before, kept 63 % of the engine's
  // blocks of 8 cells). The entries are the function at i / (n - 1), so its largest opacity
  // between the first and last entry read bounds them. The scale is increasing, so the block's
  // min and max map to the least and greatest table coordinates of its samples.
  if (!(vmin <= vmax)) return false;  // a span of no samples (all missing), or NaN
  const double last = n - 1;
  const double i0 = std::floor(normalise(vmin) * last), i1 = std::ceil(normalise(vmax) * last);
  return maxOpacityNormalised(i0 / last, i1 / last) > 0.0;
}

}  // namespace sortlast
