#pragma once
// Per-pixel rates of the compositing kernels (compositing/pixel_cost.h), as measure_rates writes
// them and the SMPI build reads them: CSV lines `work,bytes_per_pixel,ns_per_pixel`.
#include <string>

#include "compositing/pixel_cost.h"

namespace sortlast::scale {

const char* pixelWorkName(PixelWork work);

struct PixelRates {
  // ns per pixel, by work and wire format (index 0: 4 bytes per pixel, 1: 8); < 0: not measured.
  double ns[int(PixelWork::Count)][2];
  PixelRates();
  double at(PixelWork work, int bytes_per_pixel) const;  // throws if not measured
};

// Throws std::runtime_error naming the file and line on anything malformed.
PixelRates readPixelRates(const std::string& path);

// The SMPI build: the rates chargePixels uses, and the simulated host speed they refer to.
// One nanosecond of the measuring machine's core is charged as one flop, so a platform host of
// speed 1 Gflop/s ("1Gf") is that core, and "2Gf" a host twice as fast.
void usePixelRates(const PixelRates& rates);

}  // namespace sortlast::scale
