// The sortlast Python module's entry point: the exception types and the bindings of each part
// (comm.cpp, session_bindings.cpp, insitu_bindings.cpp, image_bindings.cpp). The package around
// it is python/sortlast/__init__.py.
#include "bindings.h"

namespace sortlast_py {

PyObject* g_error = nullptr;
PyObject* g_input_error = nullptr;
PyObject* g_insitu_error = nullptr;

void raiseInputError(const std::string& message) {
  PyErr_SetString(g_input_error, message.c_str());
  throw py::error_already_set();
}

void raiseInSituError(const std::string& message) {
  PyErr_SetString(g_insitu_error, message.c_str());
  throw py::error_already_set();
}

}  // namespace sortlast_py

PYBIND11_MODULE(_sortlast, m) {
  using namespace sortlast_py;
  m.doc() = "sortlast's resident session and in-situ library (use the sortlast package)";
  // sortlast.Error: every error of the module; InputError: a bad scene, request or job failure
  // (the C++ JobFailed message, the same on every rank); InSituError: the in-situ library's.
  g_error = PyErr_NewException("sortlast.Error", PyExc_RuntimeError, nullptr);
  g_input_error = PyErr_NewException("sortlast.InputError", g_error, nullptr);
  g_insitu_error = PyErr_NewException("sortlast.InSituError", g_error, nullptr);
  m.add_object("Error", py::handle(g_error));
  m.add_object("InputError", py::handle(g_input_error));
  m.add_object("InSituError", py::handle(g_insitu_error));
  bindComm(m);
  bindSession(m);
  bindInSitu(m);
  bindImages(m);
}
