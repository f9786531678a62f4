#pragma once
// The SMPI build's side of compositing/pixel_cost.h: the rates chargePixels charges (smpi_charge.cpp).
#include "compositing/pixel_rates.h"

namespace sortlast::scale {

// One nanosecond of the measuring machine's core is charged as one flop, so a platform host of
// speed 1 Gflop/s ("1Gf") is that core, and "2Gf" a host twice as fast.
void usePixelRates(const PixelRates& rates);

// Simulated seconds (MPI_Wtime) at which world rank `rank` last called markGatherStart since
// clearGatherStart(rank); 0 if it has not.
double gatherStartTime(int rank);
void clearGatherStart(int rank);

}  // namespace sortlast::scale
