#pragma once
// image.legend: a colour legend drawn into a written frame on rank 0, after compositing: a bar of
// the transfer function's colours (plain r, g, b of its table, not weighted by opacity: a haze of
// opacity 0.01 would otherwise show as black) over transfer.range, evenly spaced in
// transfer.scale as the table is, with ticks labelled in data units (decades under log), a title
// with its units, all in DejaVu Sans (io/text_raster.h). The legend's pixels are opaque; no pixel
// outside its rectangle changes.
#include <string>
#include <vector>

#include "io/image.h"
#include "scene/sections.h"
#include "transfer/transfer_function.h"

namespace sortlast {

struct LegendTick {
  double value;  // data units
  double place;  // along the bar, [0, 1] (the transfer function's normalised place)
  std::string label;
};

// About `count` ticks within the range: linear: round steps (1, 2 or 5 x 10^k); log: decades (every
// k-th when there are too many; evenly spaced in log10 when the range spans less than two);
// symlog: 0 and +-decades at or beyond the linear width.
std::vector<LegendTick> legendTicks(const TransferFunction& tf, int count);

struct LegendRect {
  int x = 0, y = 0, width = 0, height = 0;  // everything drawn, clipped to the frame
  int bar_x = 0, bar_y = 0, bar_width = 0, bar_height = 0;  // the colour bar's inside
  bool vertical = true;  // the bar runs bottom (range low) to top; else left (low) to right
};

// Draws the legend into `frame` (premultiplied RGBA8, row 0 at the top); text in black or white,
// whichever stands out from `background`. Returns where it drew. Throws InputError naming the
// font when it is missing.
LegendRect drawLegend(ImageRGBA8& frame, const TransferFunction& tf, const LegendSpec& spec,
                      const glm::dvec3& background);

}  // namespace sortlast
