#pragma once
// The data histogram a viewer draws under its transfer-function editor: kHistogramBins bins even
// in the transfer function's scale (transfer.scale) over the data's range (its low end
// transfer.range's under a log scale over data through zero: samples <= 0 in bin 0; linear where
// log has no positive end). Counted per rank, summed on rank 0.
#include <vector>

#include "scene/sections.h"
#include "transfer/value_scale.h"

namespace sortlast {

constexpr int kHistogramBins = 256;

struct ValueHistogram {
  std::vector<long long> counts;  // rank 0: kHistogramBins (other ranks: empty)
  ValueScale scale;
  double lo = 0, hi = 0;

  // The bins for data over [data_min, data_max] under `transfer` (no counts yet).
  static ValueHistogram framing(const TransferSpec& transfer, double data_min, double data_max);
};

// The bin of each value for a histogram's framing, computed once.
class HistogramBinner {
 public:
  explicit HistogramBinner(const ValueHistogram& h);
  // NaN (a missing sample): -1.
  int binOf(double v) const;

 private:
  ValueScale vs_;
  double lo_, slo_, scale_;
};

}  // namespace sortlast
