#pragma once
// The SMPI build's MPI_Probe without polling (smpi_probe.cpp).
#include <mpi.h>

namespace sortlast::scale {

// Serves an MPI_Recv from the message an earlier MPI_Probe of this rank already received, if it
// matches; returns false (and does nothing) otherwise.
bool receiveProbed(void* buf, int count, MPI_Datatype type, int source, int tag, MPI_Comm comm,
                   MPI_Status* status);

}  // namespace sortlast::scale
