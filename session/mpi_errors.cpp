#include "session/mpi_errors.h"

#include <cstdio>

#include "session/collective.h"

namespace sortlast {

namespace {

void onMpiError(MPI_Comm* comm, int* code, ...) {
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  if (MPI_Error_string(*code, text, &length) != MPI_SUCCESS)
    std::snprintf(text, sizeof text, "code %d", *code);
  int rank = -1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::fprintf(stderr,
               "sortlast: error: rank %d: MPI error while %s: %s (another rank may have died); "
               "ending the job\n",
               rank, g_phase.c_str(), text);
  std::fflush(stderr);
  MPI_Abort(*comm, 1);
}

}  // namespace

void installMpiErrorHandler(MPI_Comm comm) {
  MPI_Errhandler handler;
  MPI_Comm_create_errhandler(&onMpiError, &handler);
  MPI_Comm_set_errhandler(comm, handler);
  MPI_Errhandler_free(&handler);
}

}  // namespace sortlast
