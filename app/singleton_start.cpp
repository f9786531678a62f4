#include "app/singleton_start.h"

#include <cstdlib>
#include <initializer_list>

namespace sortlast {

void isolateSingletonStart() {
  // Launchers (Open MPI's mpirun/prterun, PMIx, Slurm's srun, Hydra) leave these for their ranks.
  for (const char* launched : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "SLURM_PROCID"})
    if (std::getenv(launched)) return;
  setenv("OMPI_MCA_ess_singleton_isolated", "1", /*overwrite=*/0);
}

}  // namespace sortlast
