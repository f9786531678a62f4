#pragma once
// MPI errors as messages. MPI's default handler (MPI_ERRORS_ARE_FATAL) aborts the job with, at
// best, the library's own text; this one prints which rank met which error (MPI_Error_string)
// while doing what (the job's phase, session/collective.h), then aborts: a rank that met an MPI
// error cannot take part in the job's collectives any more, so ending the job is the one way no
// rank is left waiting.
#include <mpi.h>

namespace sortlast {

// Installs the handler on `comm` (and communicators later derived from it inherit it).
void installMpiErrorHandler(MPI_Comm comm);

}  // namespace sortlast
