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
#include <new>
#include <string>
#include <utility>

#include "common/error.h"

namespace sortlast {

// Every rank throws it with the same message: the first failing rank's (a resident session answers
// a client with it and goes on).
struct JobFailed {
  std::string message;
};

// What the job is doing (set by PhaseScope), so an allocation that fails despite the memory
// estimate (session/memory_budget.h) still says where: the last resort before std::bad_alloc.
inline thread_local std::string g_phase = "starting";

struct PhaseScope {
  explicit PhaseScope(std::string phase) : saved_(std::move(g_phase)) {
    g_phase = std::move(phase);
  }
  ~PhaseScope() { g_phase = std::move(saved_); }
  PhaseScope(const PhaseScope&) = delete;
  PhaseScope& operator=(const PhaseScope&) = delete;

 private:
  std::string saved_;
};

inline std::string outOfMemoryMessage() {
  return "out of memory while " + g_phase +
         " (std::bad_alloc): the scene needs more memory than this rank could allocate; "
         "lower limits.memory_mib to have such scenes refused up front, or use fewer samples, "
         "particles or pixels per rank";
}

// `while_waiting` runs over and over while this rank waits for the others to finish the step
// (the failure flag is reduced without blocking), so a rank that is done early can do useful
// work meanwhile: rank 0 blends brick images that have arrived. It must not throw.
template <class Step, class Idle>
void collectively(MPI_Comm comm, Step&& step, Idle&& while_waiting) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::string message;
  try {
    step();
  } catch (const InputError& e) {
    message = e.what();
  } catch (const std::bad_alloc&) {
    message =
        (size > 1 ? "rank " + std::to_string(rank) + ": " : std::string()) + outOfMemoryMessage();
  } catch (const std::exception& e) {
    message = (size > 1 ? "rank " + std::to_string(rank) + ": " : std::string()) + e.what();
  }
  int mine = message.empty() ? INT_MAX : rank, first = INT_MAX;
  MPI_Request request;
  MPI_Iallreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm, &request);
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) break;
    if (message.empty()) while_waiting();
  }
  if (first == INT_MAX) return;
  if (rank == first) std::fprintf(stderr, "sortlast: error: %s\n", message.c_str());
  // Every rank learns the message (all know `first`, so this is a matched collective).
  int length = int(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  message.resize(size_t(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, first, comm);
  throw JobFailed{message};
}

template <class Step>
void collectively(MPI_Comm comm, Step&& step) {
  collectively(comm, std::forward<Step>(step), [] {});
}

}  // namespace sortlast
