// sortlast.Session (and through it sortlast.render): a thin client of the resident session
// (session/render_session.h), driven the way `sortlast render` drives it
// (app/render_job.cpp). Long calls release the GIL; a JobFailed becomes sortlast.InputError
// with its message on every rank, and the session stays usable.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>

#include "bindings.h"
#include "scene/scene.h"
#include "session/collective.h"
#include "session/render_session.h"

namespace sortlast_py {

namespace {

using sortlast::FrameRequest;
using sortlast::FrameResult;
using sortlast::JobFailed;
using sortlast::RenderSession;
using sortlast::SessionOptions;

// A std::vector's pixels as a numpy array (H, W, 4) without copying: the array owns the vector.
template <class T>
py::array pixels(std::vector<T>&& px, int width, int height) {
  auto* owned = new std::vector<T>(std::move(px));
  py::capsule free_it(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({py::ssize_t(height), py::ssize_t(width), py::ssize_t(4)}, owned->data(),
                        free_it);
}

class Session {
 public:
  // scene_path: a scene file ("" with scene_yaml empty: the built-in scene); scene_yaml: the
  // scene's text instead (scene_name names it in messages; relative paths resolve from the
  // working directory).
  Session(const std::string& scene_path, const std::string& scene_yaml, const std::string& scene_name,
          std::vector<std::string> overrides, const py::object& comm, bool resident, bool quiet) {
    MPI_Comm user = commOf(comm);
    comm_ = duplicate(user);
    MPI_Comm_rank(comm_, &rank_);
    SessionOptions so;
    so.overrides = std::move(overrides);
    so.resident = resident;
    so.quiet = quiet;
    std::optional<std::string> failed;
    {
      py::gil_scoped_release nogil;
      try {
        if (!scene_yaml.empty() || scene_path.empty())
          so.scene = {scene_yaml.empty() ? std::string() : scene_name, scene_yaml};
        else
          sortlast::collectively(comm_, [&] { so.scene = sortlast::readSceneText(scene_path); });
        session_ = std::make_unique<RenderSession>(std::move(so), comm_);
      } catch (const JobFailed& e) {
        failed = e.message;
      }
    }
    if (failed) {
      releaseComm(comm_);
      raiseInputError(*failed);
    }
  }

  ~Session() { close(); }

  void close() {
    if (session_) {
      py::gil_scoped_release nogil;
      session_.reset();
    }
    releaseComm(comm_);
  }

  // Collective. Rank 0: (image uint8, image float32 or None, stats JSON text, background);
  // other ranks: None.
  py::object frame(std::vector<std::string> overrides, int orbit_frame, bool float_frame) {
    RenderSession& s = open();
    FrameRequest request;
    request.overrides = std::move(overrides);
    request.orbit_frame = orbit_frame;
    request.float_frame = float_frame;
    FrameResult result;
    std::optional<std::string> failed;
    {
      py::gil_scoped_release nogil;
      try {
        result = s.render(request);
      } catch (const JobFailed& e) {
        failed = e.message;
      }
    }
    if (failed) raiseInputError(*failed);
    if (rank_ != 0) return py::none();
    const glm::dvec3 bg = result.scene.image.background;
    const int w = result.image.width, h = result.image.height;
    py::object image_f = py::none();
    if (float_frame) image_f = pixels(std::move(result.image_f.px), w, h);
    return py::make_tuple(pixels(std::move(result.image.px), w, h), image_f, result.stats.dump(),
                          py::make_tuple(bg.x, bg.y, bg.z));
  }

  py::object describe() {
    RenderSession& s = open();
    if (rank_ != 0) return py::none();
    return py::str(s.describe().dump());
  }

  py::object jobStats() {
    RenderSession& s = open();
    if (rank_ != 0) return py::none();
    nlohmann::json top{{"renderer", s.rendererDescription()}, {"particles", s.particleCount()}};
    top.update(s.jobStats());
    return py::str(top.dump());
  }

  int orbitFrames() { return open().orbitFrames(); }
  int rank() const { return rank_; }
  bool closed() const { return !session_; }

 private:
  RenderSession& open() {
    if (!session_) raiseInputError("the session is closed");
    return *session_;
  }
  std::unique_ptr<RenderSession> session_;
  MPI_Comm comm_ = MPI_COMM_NULL;  // our duplicate of the caller's communicator
  int rank_ = 0;
};

}  // namespace

void bindSession(py::module_& m) {
  py::class_<Session>(m, "_Session")
      .def(py::init<const std::string&, const std::string&, const std::string&,
                    std::vector<std::string>, const py::object&, bool, bool>(),
           py::arg("scene_path"), py::arg("scene_yaml"), py::arg("scene_name"), py::arg("overrides"),
           py::arg("comm"), py::arg("resident"), py::arg("quiet"))
      .def("frame", &Session::frame, py::arg("overrides"), py::arg("orbit_frame"), py::arg("float_frame"))
      .def("describe", &Session::describe)
      .def("job_stats", &Session::jobStats)
      .def("orbit_frames", &Session::orbitFrames)
      .def("close", &Session::close)
      .def_property_readonly("rank", &Session::rank)
      .def_property_readonly("closed", &Session::closed);
}

}  // namespace sortlast_py
