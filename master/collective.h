#pragma once
// Errors on any rank end the job on every rank, cleanly. Each phase of a frame runs through
// `collectively`: the step runs on every rank; if it threw anywhere, all ranks learn it from one
// Allreduce, the lowest failing rank prints its message, and every rank throws JobFailed, which
// main() turns into MPI_Finalize and a non-zero exit. No rank is left waiting for a message that
// will never come.
#include <mpi.h>

#include <climits>
#include <cstdio>
#include <exception>
#include <string>

#include "common/error.h"

namespace sortlast {

struct JobFailed {};

template <class Step>
void collectively(MPI_Comm comm, Step&& step) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::string message;
  try {
    step();
  } catch (const InputError& e) {
    message = e.what();
  } catch (const std::exception& e) {
    message = (size > 1 ? "rank " + std::to_string(rank) + ": " : std::string()) + e.what();
  }
  int mine = message.empty() ? INT_MAX : rank, first = INT_MAX;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == INT_MAX) return;
  if (rank == first) std::fprintf(stderr, "sortlast: error: %s\n", message.c_str());
  throw JobFailed{};
}

}  // namespace sortlast
