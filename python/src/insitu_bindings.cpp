// sortlast.InSitu: a thin client of the in-situ library (include/sortlast/insitu.h). publish()
// describes numpy arrays where they lie (arrays.h) and keeps a reference to each until execute()
// returns; its checks end collectively (every rank raises the failing rank's message), so no rank
// goes on to execute() alone. execute() releases the GIL.
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <optional>

#include "arrays.h"
#include "bindings.h"
#include "common/error.h"
#include "session/collective.h"

namespace sortlast_py {

namespace {

class InSitu {
 public:
  InSitu(const py::object& comm, const std::string& actions, bool from_text) {
    MPI_Comm c = commOf(comm);
    std::optional<std::string> failed;
    {
      py::gil_scoped_release nogil;
      try {
        vis_ = std::make_unique<sortlast::InSitu>(from_text ? sortlast::InSitu::fromText(c, actions)
                                                            : sortlast::InSitu(c, actions));
      } catch (const sortlast::InSituError& e) {
        failed = e.what();
      }
    }
    if (failed) raiseInSituError(*failed);
    check_comm_ = duplicate(c);
    MPI_Comm_size(check_comm_, &size_);
  }
  ~InSitu() { close(); }

  void close() {
    held_ = py::list();
    if (vis_) {
      py::gil_scoped_release nogil;
      vis_.reset();
    }
    releaseComm(check_comm_);
  }

  // Collective. `problem`: what the package found wrong with the arguments on this rank (it is
  // raised on every rank, like the checks here).
  void publish(long long step, double time, const py::object& grid, std::array<int, 3> ghost_lo,
               std::array<int, 3> ghost_hi, std::array<double, 3> origin, std::array<double, 3> spacing,
               const std::string& name, const py::object& particles,
               const std::map<std::string, double>& quantities, const std::string& problem) {
    sortlast::InSitu& vis = open();
    sortlast::Published data;
    try {
      sortlast::collectively(check_comm_, [&] {
        if (!problem.empty()) throw sortlast::InputError(rankPrefix() + problem);
        try {
          if (!grid.is_none()) data.grid = gridBlock(grid, ghost_lo, ghost_hi, origin, spacing, name);
          if (!particles.is_none()) data.particles = particleBlock(particles);
        } catch (const sortlast::InputError& e) {
          throw sortlast::InputError(rankPrefix() + e.what());
        }
        data.quantities = quantities;
      });
    } catch (const sortlast::JobFailed& e) {
      raiseInSituError("sortlast in situ: publish: " + e.message);
    }
    vis.publish(step, time, data);
    // The arrays stay alive (and numpy refuses to resize them) until execute() returns.
    held_ = py::list();
    held_.append(grid);
    held_.append(particles);
  }

  py::dict execute() {
    sortlast::InSitu& vis = open();
    sortlast::ExecuteReport r;
    std::optional<std::string> failed;
    {
      py::gil_scoped_release nogil;
      try {
        r = vis.execute();
      } catch (const sortlast::InSituError& e) {
        failed = e.what();
      }
    }
    held_ = py::list();
    if (failed) raiseInSituError(*failed);
    py::dict d;
    d["rendered"] = r.rendered;
    d["images"] = r.images;
    d["error"] = r.error;
    d["seconds"] = r.seconds;
    d["memory_added_mib"] = r.memory_added_mib;
    d["texture_mib"] = r.texture_mib;
    d["gl_vendor"] = r.gl_vendor;
    d["gl_renderer"] = r.gl_renderer;
    d["host"] = r.host;
    d["device"] = r.device;
    return d;
  }

  py::list held() const { return held_; }
  bool closed() const { return !vis_; }

 private:
  sortlast::InSitu& open() {
    if (!vis_) raiseInSituError("sortlast in situ: this InSitu is closed");
    return *vis_;
  }
  std::string rankPrefix() const {
    if (size_ < 2) return "";
    int rank = 0;
    MPI_Comm_rank(check_comm_, &rank);
    return "rank " + std::to_string(rank) + ": ";
  }
  std::unique_ptr<sortlast::InSitu> vis_;
  MPI_Comm check_comm_ = MPI_COMM_NULL;  // publish's checks, apart from the library's messages
  int size_ = 1;
  py::list held_;
};

}  // namespace

void bindInSitu(py::module_& m) {
  py::class_<InSitu>(m, "_InSitu")
      .def(py::init<const py::object&, const std::string&, bool>(), py::arg("comm"), py::arg("actions"),
           py::arg("from_text"))
      .def("publish", &InSitu::publish, py::arg("step"), py::arg("time"), py::arg("grid"),
           py::arg("ghost_lo"), py::arg("ghost_hi"), py::arg("origin"), py::arg("spacing"),
           py::arg("name"), py::arg("particles"), py::arg("quantities"), py::arg("problem"))
      .def("execute", &InSitu::execute)
      .def("close", &InSitu::close)
      .def_property_readonly("held", &InSitu::held)
      .def_property_readonly("closed", &InSitu::closed);
}

}  // namespace sortlast_py
