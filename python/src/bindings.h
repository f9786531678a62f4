#pragma once
// What the binding files of the sortlast Python module share (python/CMakeLists.txt).
#include <mpi.h>
#include <pybind11/pybind11.h>

#include <string>

namespace sortlast_py {

namespace py = pybind11;

// comm.cpp: MPI for Python callers.
// Initialises MPI (MPI_THREAD_FUNNELED) unless something (mpi4py, the program) already did.
void ensureMpi();
// None: MPI_COMM_WORLD (initialising MPI if needed); an mpi4py communicator: its MPI_Comm.
MPI_Comm commOf(const py::object& comm);
// A private duplicate for one object's collective checks (freed by releaseComm).
MPI_Comm duplicate(MPI_Comm comm);
void releaseComm(MPI_Comm& comm);

// The exception types (module.cpp): sortlast.Error and its subclasses.
extern PyObject* g_error;
extern PyObject* g_input_error;
extern PyObject* g_insitu_error;
// Raises sortlast.InputError / InSituError with `message` (throws py::error_already_set).
[[noreturn]] void raiseInputError(const std::string& message);
[[noreturn]] void raiseInSituError(const std::string& message);

void bindComm(py::module_& m);
void bindSession(py::module_& m);
void bindInSitu(py::module_& m);
void bindImages(py::module_& m);

}  // namespace sortlast_py
