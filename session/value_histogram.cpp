#include "session/value_histogram.h"

#include <algorithm>
#include <cmath>

namespace sortlast {

ValueHistogram ValueHistogram::framing(const TransferSpec& transfer, double data_min, double data_max) {
  ValueHistogram h;
  h.scale = ValueScale{transfer.scale, transfer.linear_width};
  h.lo = data_min, h.hi = data_max;
  if (h.scale.kind == ValueScaleKind::kLog && !(h.lo > 0.0) && transfer.range) h.lo = transfer.range->first;
  if (h.scale.kind == ValueScaleKind::kLog && !(h.lo > 0.0 && h.hi > h.lo)) h.scale = ValueScale{}, h.lo = data_min;
  return h;
}

HistogramBinner::HistogramBinner(const ValueHistogram& h)
    : vs_(h.scale), lo_(h.lo), slo_(h.scale.apply(h.lo)), scale_(0.0) {
  const double shi = h.scale.apply(h.hi);
  scale_ = shi > slo_ ? kHistogramBins / (shi - slo_) : 0.0;
}

int HistogramBinner::binOf(double v) const {
  if (std::isnan(v)) return -1;
  const double t = vs_.kind == ValueScaleKind::kLinear ? (v - lo_) * scale_
                   : vs_.kind == ValueScaleKind::kLog && !(v > 0.0) ? 0.0
                                                                     : (vs_.apply(v) - slo_) * scale_;
  return std::clamp(int(std::clamp(t, 0.0, double(kHistogramBins))), 0, kHistogramBins - 1);
}

}  // namespace sortlast
