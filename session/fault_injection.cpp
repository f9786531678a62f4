#include "session/fault_injection.h"

#include <mpi.h>

#include <cstdlib>
#include <stdexcept>

namespace sortlast {

namespace {

bool namesRank(const char* var, int rank) {
  const char* v = std::getenv(var);
  return v && std::atoi(v) == rank;
}

}  // namespace

FrameFaults FrameFaults::fromEnvironment(int rank) {
  FrameFaults f;
  f.fail_ = namesRank("SORTLAST_TEST_FAIL_RANK", rank);
  f.crash_ = namesRank("SORTLAST_TEST_CRASH_RANK", rank);
  f.mpi_error_ = namesRank("SORTLAST_TEST_MPI_ERROR_RANK", rank);
  f.fail_after_brick_ = namesRank("SORTLAST_TEST_FAIL_RANK_AFTER_BRICK", rank);
  return f;
}

void FrameFaults::beforeBricks() const {
  if (fail_) throw std::runtime_error("injected failure (SORTLAST_TEST_FAIL_RANK)");
  if (crash_) std::abort();
  if (mpi_error_) {  // a send to a rank that does not exist: an MPI error
    int size = 1, unused = 0;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    MPI_Send(&unused, 1, MPI_INT, size + 7, 0, MPI_COMM_WORLD);
  }
}

void FrameFaults::afterBrick() const {
  if (fail_after_brick_)
    throw std::runtime_error("injected failure after a brick (SORTLAST_TEST_FAIL_RANK_AFTER_BRICK)");
}

}  // namespace sortlast
