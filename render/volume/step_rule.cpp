#include "render/volume/step_rule.h"

#include <algorithm>
#include <cmath>

namespace sortlast {

StepRule::StepRule(const std::vector<float>& table, double lo, double hi, double delta,
                   double tolerance, int max_multiple, ValueScale scale)
    : n_(int(table.size() / 4)), lo_(lo), hi_(hi), delta_(delta), tolerance_(tolerance),
      scale_(scale), slo_(scale.apply(lo)), shi_(scale.apply(hi)), max_level_(0) {
  while ((2 << max_level_) <= max_multiple) ++max_level_;
  for (int c = 0; c < 4; ++c) {
    // Channel c of the emission-absorption pair: tau, then colour times tau.
    std::vector<float> v(static_cast<size_t>(n_));
    for (int i = 0; i < n_; ++i) {
      const float tau = table[4 * size_t(i) + 3];
      v[size_t(i)] = c == 3 ? tau : table[4 * size_t(i) + size_t(c)] * tau;
    }
    min_[c].push_back(v);
    max_[c].push_back(v);
    for (int l = 1; (1 << l) <= n_; ++l) {
      const std::vector<float>&pmin = min_[c][size_t(l - 1)], &pmax = max_[c][size_t(l - 1)];
      std::vector<float> nmin(size_t(n_ - (1 << l) + 1)), nmax(nmin.size());
      for (size_t i = 0; i < nmin.size(); ++i) {
        nmin[i] = std::min(pmin[i], pmin[i + (size_t(1) << (l - 1))]);
        nmax[i] = std::max(pmax[i], pmax[i + (size_t(1) << (l - 1))]);
      }
      min_[c].push_back(std::move(nmin));
      max_[c].push_back(std::move(nmax));
    }
  }
}

double StepRule::oscillation(int i0, int i1) const {
  int l = 0;
  while ((2 << l) <= i1 - i0 + 1) ++l;
  const size_t a = size_t(i0), b = size_t(i1 - (1 << l) + 1);
  double osc = 0.0;
  for (int c = 0; c < 4; ++c) {
    const auto &mn = min_[c][size_t(l)], &mx = max_[c][size_t(l)];
    osc = std::max(osc, double(std::max(mx[a], mx[b])) - double(std::min(mn[a], mn[b])));
  }
  return osc;
}

int StepRule::level(float vmin, float vmax) const {
  if (max_level_ == 0 || !(vmin <= vmax)) return 0;
  // Table coordinate of a value (entries at integers), clamped as the shader clamps; the filtered
  // lookup blends the entries on either side of it.
  // The scale is increasing (log: v <= 0 below the range), so min and max bound the coordinates.
  auto coord = [&](double v) {
    if (scale_.kind == ValueScaleKind::kLinear) return std::clamp((v - lo_) / (hi_ - lo_), 0.0, 1.0) * (n_ - 1);
    if (scale_.kind == ValueScaleKind::kLog && !(v > 0.0)) return 0.0;
    return std::clamp((scale_.apply(v) - slo_) / (shi_ - slo_), 0.0, 1.0) * (n_ - 1);
  };
  const int i0 = std::max(0, int(std::floor(coord(vmin)))), i1 = std::min(n_ - 1, int(std::ceil(coord(vmax))));
  const double osc = oscillation(i0, i1);
  int j = 0;
  while (j < max_level_ && double(2 << j) * delta_ * osc <= tolerance_) ++j;
  return j;
}

int StepRule::maxMultiple(double delta, double min_spacing) {
  int m = 1;
  while (m < 8 && 2.0 * m * delta <= 2.0 * min_spacing) m *= 2;
  return m;
}

}  // namespace sortlast
