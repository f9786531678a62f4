#pragma once
// Per-pixel rates of the compositing kernels (pixel_cost.h): what one pixel of each kind of work
// costs on one core. Two users: the strategy cost model (strategy_model.h), which forecasts a
// frame's compositing time to choose a strategy, and the SMPI build (docs/smpi.md), which charges
// them as simulated computation. Measured by build/bench/measure_rates, which writes CSV lines
// `work,bytes_per_pixel,ns_per_pixel` (results/scale/rates.csv).
#include <string>

#include "compositing/pixel_cost.h"

namespace sortlast {

const char* pixelWorkName(PixelWork work);

struct PixelRates {
  // ns per pixel, by work and wire format (index 0: 4 bytes per pixel, 1: 8); < 0: not measured.
  double ns[int(PixelWork::Count)][2];
  PixelRates();
  double at(PixelWork work, int bytes_per_pixel = 4) const;  // throws if not measured
};

// Throws std::runtime_error naming the file and line on anything malformed.
PixelRates readPixelRates(const std::string& path);

// The rates measured on the development machine (one core of a 2-core cloud VM, under load;
// results/scale/rates.csv of 2026-12-05): what `compositing.strategy: auto` forecasts with. Only
// their ratios to one another and to the network's figures decide a choice.
PixelRates measuredPixelRates();

}  // namespace sortlast
