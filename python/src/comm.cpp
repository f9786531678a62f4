// MPI for Python callers: communicators from mpi4py (through its C API, PyMPIComm_Get), or
// MPI_COMM_WORLD, initialising MPI when nothing did (then finalised at exit by the package).
#include <mpi4py/mpi4py.h>

#include "bindings.h"

namespace sortlast_py {

namespace {
bool g_we_initialised = false;
bool g_mpi4py_imported = false;
}  // namespace

void ensureMpi() {
  int initialised = 0, finalised = 0;
  MPI_Finalized(&finalised);
  if (finalised) raiseInputError("MPI was already finalised: sortlast cannot run after MPI_Finalize");
  MPI_Initialized(&initialised);
  if (initialised) return;
  int provided = 0;
  // The renderer's own threads never call MPI; funneled is what `sortlast` asks for too.
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    raiseInputError("MPI_Init_thread failed");
  g_we_initialised = true;
}

MPI_Comm commOf(const py::object& comm) {
  if (comm.is_none()) {
    ensureMpi();
    return MPI_COMM_WORLD;
  }
  if (!g_mpi4py_imported) {
    if (import_mpi4py() < 0) throw py::error_already_set();
    g_mpi4py_imported = true;
  }
  if (!PyObject_TypeCheck(comm.ptr(), &PyMPIComm_Type))
    throw py::type_error("comm must be an mpi4py communicator (mpi4py.MPI.Comm) or None, not " +
                         std::string(py::str(py::type::of(comm).attr("__name__"))));
  MPI_Comm* c = PyMPIComm_Get(comm.ptr());
  if (!c) throw py::error_already_set();
  if (*c == MPI_COMM_NULL) throw py::value_error("comm is MPI.COMM_NULL");
  ensureMpi();  // mpi4py initialised it; this only checks it is not finalised
  return *c;
}

MPI_Comm duplicate(MPI_Comm comm) {
  MPI_Comm d = MPI_COMM_NULL;
  MPI_Comm_dup(comm, &d);
  return d;
}

void releaseComm(MPI_Comm& comm) {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (comm != MPI_COMM_NULL && !finalised) MPI_Comm_free(&comm);
  comm = MPI_COMM_NULL;
}

void bindComm(py::module_& m) {
  m.def("_mpi_initialised_by_sortlast", [] { return g_we_initialised; });
  m.def("_init_mpi", [] { ensureMpi(); });
  // Called at exit by the package (after closing every session): only if the module initialised it.
  m.def("_finalize_mpi", [] {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (g_we_initialised && !finalised) MPI_Finalize();
  });
  m.def("_rank_size", [](const py::object& comm) {
    MPI_Comm c = commOf(comm);
    int rank = 0, size = 1;
    MPI_Comm_rank(c, &rank);
    MPI_Comm_size(c, &size);
    return py::make_tuple(rank, size);
  }, py::arg("comm") = py::none());
}

}  // namespace sortlast_py
