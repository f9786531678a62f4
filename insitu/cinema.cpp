#include "insitu/cinema.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <system_error>

#include "common/error.h"
#include "insitu/output_names.h"

namespace sortlast {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Viewers substitute the parameter values of info.json into name_pattern, so an angle must read
// the same in a file name as in the index: the shortest text that reads back as the same double
// (90, 22.5), which is also how JSON numbers print in a browser.
std::string angleLabel(double deg) {
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, deg == 0.0 ? 0.0 : deg);
  return std::string(buf, end);
}

// Whole angles as JSON integers: a viewer in Python would print 90.0 and miss the file "90_0.png".
nlohmann::ordered_json angleValue(double deg) {
  if (deg == std::floor(deg) && std::abs(deg) < 1e15) return static_cast<long long>(deg);
  return deg;
}

nlohmann::ordered_json angleParameter(const char* label, const std::vector<double>& angles) {
  nlohmann::ordered_json values = nlohmann::ordered_json::array();
  for (double a : angles) values.push_back(angleValue(a));
  // The view nearest the base camera's is the one to show first.
  double best = angles.front();
  for (double a : angles)
    if (std::abs(a) < std::abs(best)) best = a;
  return {{"type", "range"}, {"label", label}, {"values", values}, {"default", angleValue(best)}};
}

}  // namespace

glm::dvec3 cinemaPosition(const glm::dvec3& look_at, const glm::dvec3& base_position,
                          const glm::dvec3& up, double phi_deg, double theta_deg) {
  if (!(theta_deg > -90.0 && theta_deg < 90.0))
    throw InputError("cinema theta " + angleLabel(theta_deg) + ": must be in (-90, 90) degrees");
  if (glm::length(up) == 0.0) throw InputError("cinema: camera.up must not be zero");
  const glm::dvec3 offset = base_position - look_at;
  const double radius = glm::length(offset);
  if (!(radius > 0.0)) throw InputError("cinema: the camera sits on camera.look_at");
  // An orthonormal frame around up whose azimuth 0 is the base camera's, as an orbit's
  // (common/camera.cpp orbitCamera); a camera straight above look_at has no azimuth, so any
  // direction perpendicular to up stands in.
  const glm::dvec3 axis = glm::normalize(up);
  glm::dvec3 start = offset - glm::dot(offset, axis) * axis;
  if (glm::length(start) < 1e-12 * radius)
    start = std::abs(axis.z) < 0.9 ? glm::cross(axis, glm::dvec3(0, 0, 1))
                                   : glm::cross(axis, glm::dvec3(1, 0, 0));
  const glm::dvec3 e1 = glm::normalize(start), e2 = glm::cross(axis, e1);
  const double az = phi_deg * kDegree, el = theta_deg * kDegree;
  return look_at +
         radius * (std::cos(el) * (std::cos(az) * e1 + std::sin(az) * e2) + std::sin(el) * axis);
}

CinemaIndex::CinemaIndex(CinemaSpec spec) : spec_(std::move(spec)) {}

std::string CinemaIndex::imagePath(long long step, double phi, double theta) const {
  return stepLabel(step) + "/" + angleLabel(phi) + "_" + angleLabel(theta) + ".png";
}

void CinemaIndex::addStep(long long step, double time, const std::vector<std::string>& images) {
  auto it = std::lower_bound(steps_.begin(), steps_.end(), step,
                             [](const StepEntry& e, long long s) { return e.step < s; });
  if (it != steps_.end() && it->step == step)
    *it = {step, time, images};
  else
    steps_.insert(it, {step, time, images});
}

void CinemaIndex::write() const {
  nlohmann::ordered_json times = nlohmann::ordered_json::array();
  nlohmann::ordered_json steps = nlohmann::ordered_json::array();
  for (const StepEntry& e : steps_) {
    times.push_back(stepLabel(e.step));
    steps.push_back({{"step", e.step}, {"time", e.time}, {"images", e.images}});
  }
  nlohmann::ordered_json time_param = {{"type", "range"}, {"label", "time"}, {"values", times}};
  if (!steps_.empty()) time_param["default"] = times.front();
  nlohmann::ordered_json info = {{"type", "simple"},
                                 {"version", "1.1"},
                                 {"metadata", {{"type", "parametric-image-stack"}}},
                                 {"name_pattern", "{time}/{phi}_{theta}.png"},
                                 {"parameter_list",
                                  {{"time", time_param},
                                   {"phi", angleParameter("phi", spec_.phi)},
                                   {"theta", angleParameter("theta", spec_.theta)}}},
                                 {"steps", steps}};

  namespace fs = std::filesystem;
  const fs::path dir(spec_.directory), file = dir / "info.json", tmp = dir / "info.json.tmp";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("cinema directory " + dir.string() + ": cannot create: " + ec.message());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << info.dump(1) << "\n";
    if (!out.flush()) throw InputError("cinema index " + tmp.string() + ": cannot write");
  }
  fs::rename(tmp, file, ec);
  if (ec) throw InputError("cinema index " + file.string() + ": cannot replace: " + ec.message());
}

}  // namespace sortlast
