#pragma once
// Where one integration step crosses the transfer function's kinks (TransferFunction::kinkValues:
// its points and the range's clamp, where a channel's slope changes). The references cut their
// steps there: a quadrature rule is first order across a kink and of its full order on each
// smooth part (reference/reference.h says what that buys on a sharp function).
#include <algorithm>
#include <utility>
#include <vector>

namespace sortlast {

constexpr int kMaxStepCuts = 8;  // more kinks inside one step's values are left uncut

// The places in (ta, tb) where values running from va to vb (taken as linear between the ends)
// meet a kink, each with the kink's value, in the order the ray meets them; returns how many (at
// most kMaxStepCuts; none where an end is missing, NaN).
inline int stepCuts(const std::vector<double>& kinks, double ta, double tb, double va, double vb,
                    std::pair<double, double> (&cuts)[kMaxStepCuts]) {
  const double vlo = std::min(va, vb), vhi = std::max(va, vb);
  int m = 0;
  auto k = std::upper_bound(kinks.begin(), kinks.end(), vlo);
  for (; k != kinks.end() && *k < vhi && m < kMaxStepCuts; ++k)
    cuts[m++] = {ta + (tb - ta) * ((*k - va) / (vb - va)), *k};
  std::sort(cuts, cuts + m);
  return m;
}

}  // namespace sortlast
