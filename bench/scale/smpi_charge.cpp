// The SMPI build's chargePixels (compositing/pixel_cost.h): the pixels of each compositing kernel
// become simulated computation on the calling rank's host, at the rates measured by
// measure_rates, one flop per nanosecond of the measuring machine's core (pixel_rates.h). The run
// itself is not timed (smpirun --cfg=smpi/simulate-computation:no), so the simulated times do not
// depend on how busy the simulating machine is.
#include <mpi.h>
#include <smpi/smpi.h>

#include "bench/scale/smpi_charge.h"

namespace sortlast {

namespace {
// Shared by every simulated rank (SMPI runs them in one process, without privatising globals):
// every rank sets the same table before its first composite, and nothing writes it after.
PixelRates g_rates;
// Per world rank, for the same reason (each rank writes only its own entry).
constexpr int kMaxRanks = 1 << 16;
double g_gather_start[kMaxRanks];

int worldRank() {
  int r = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
}  // namespace

void scale::usePixelRates(const PixelRates& rates) { g_rates = rates; }

double scale::gatherStartTime(int rank) { return g_gather_start[rank]; }
void scale::clearGatherStart(int rank) { g_gather_start[rank] = 0; }

void markGatherStart() { g_gather_start[worldRank()] = MPI_Wtime(); }

void chargePixels(PixelWork work, long long pixels, int bytes_per_pixel) {
  if (pixels <= 0) return;
  smpi_execute_flops(double(pixels) * g_rates.at(work, bytes_per_pixel));
}

}  // namespace sortlast
