#pragma once
// The transfer section (transfer.*): the transfer function as the scene gives it, resolved against
// the data by build(). Rows: transfer.cpp.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "transfer/transfer_function.h"

namespace sortlast {

struct TransferSpec {
  std::vector<TfPoint> points;  // with transfer.colormap's colours applied, if it is set
  std::string colormap;         // transfer.colormap as given (empty: none)
  std::optional<std::pair<double, double>> range;  // unset: the data's global min and max
  std::optional<double> unit_length;               // unset: the smallest voxel spacing
  int table_size = 4096;
  bool preintegrated = false;  // segments from a pre-integrated 2D table (transfer/preintegration.h)

  // Resolves the automatic parts against the data.
  TransferFunction build(double data_min, double data_max, double min_spacing) const;
};

// transfer.preintegrated `auto` turns pre-integration on where the opacity changes steeply: some
// stretch between control points changes it by kSteepOpacitySlope x the stretch's width (in the
// normalised range), i.e. by 0.5 or more within 10 % of the range. Measured (results/accuracy, 0.5
// voxel): on neghip's narrow band it gains 13 dB (34.8 -> 48.0) for 10 % more time; on smooth
// functions (the engine's ramp, slope 1; the head CT's, 3.5; the default preset's, 1.5) it gains
// nothing or loses (engine 53.2 -> 48.0 dB) and costs 50-70 % more time.
inline constexpr double kSteepOpacitySlope = 5.0;
bool hasSteepOpacity(const std::vector<TfPoint>& points);

}  // namespace sortlast
