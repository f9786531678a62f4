// How a one-process run starts MPI without a launcher (`sortlast render` typed without mpirun).
#pragma once

namespace sortlast {

// Open MPI starts a one-process job that mpirun did not launch (a "singleton") by forking a
// supporting daemon, orted, so that the process could spawn more later. sortlast never spawns, and
// the daemon costs about a third of a small frame's CPU (perf, 96² two-field frame on llvmpipe:
// 643 ms task-clock with it, 450 ms without). Where no launcher's variables are set, this asks Open
// MPI not to start it (ess_singleton_isolated), unless the user has set that parameter already.
// Other MPI libraries ignore the variable. Call before MPI_Init.
void isolateSingletonStart();

}  // namespace sortlast
