#include "common/camera.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace sortlast {

namespace {
constexpr double kPi = 3.14159265358979323846;
double tanHalfFov(double fov_deg) { return std::tan(0.5 * fov_deg * kPi / 180.0); }
}  // namespace

glm::dvec2 Camera::screenScale() const {
  const double aspect = double(width) / height;
  const double s = orthographic() ? parallel_scale : tanHalfFov(fov_deg);
  return {s * aspect, s};
}

CameraRay Camera::pixelRay(double px, double py) const {
  const glm::dvec2 scale = screenScale();
  double sx = (2.0 * (px + 0.5) / width - 1.0) * scale.x;
  double sy = (1.0 - 2.0 * (py + 0.5) / height) * scale.y;
  if (orthographic()) return {position + sx * right() + sy * trueUp(), forward()};
  return {position, glm::normalize(forward() + sx * right() + sy * trueUp())};
}

glm::mat4 Camera::viewProjection(double near_plane, double far_plane) const {
  glm::dmat4 view = glm::lookAt(position, look_at, up);
  const glm::dvec2 s = screenScale();
  glm::dmat4 proj = orthographic()
                        ? glm::ortho(-s.x, s.x, -s.y, s.y, near_plane, far_plane)
                        : glm::perspective(fov_deg * kPi / 180.0, double(width) / height,
                                           near_plane, far_plane);
  glm::dmat4 flip = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, -1.0, 1.0));
  return glm::mat4(flip * proj * view);
}

std::optional<glm::dvec2> Camera::project(const glm::dvec3& p) const {
  glm::dvec3 d = p - position;
  double z = glm::dot(d, forward());
  if (z <= 0.0) return std::nullopt;
  const glm::dvec2 s = screenScale();
  const double w = orthographic() ? 1.0 : z;  // perspective divides by the depth
  double sx = glm::dot(d, right()) / (w * s.x), sy = glm::dot(d, trueUp()) / (w * s.y);
  return glm::dvec2((sx + 1.0) * 0.5 * width, (1.0 - sy) * 0.5 * height);
}

Camera orbitCamera(const Camera& base, const glm::dvec3& centre, double radius,
                   double elevation_deg, int i, int n, double start_deg) {
  // Orthonormal frame around the orbit axis (base.up); azimuth 0 is the base camera's direction.
  glm::dvec3 axis = glm::normalize(base.up);
  glm::dvec3 start = base.position - centre;
  start -= glm::dot(start, axis) * axis;
  if (glm::length(start) < 1e-12 * radius) {
    start = std::abs(axis.z) < 0.9 ? glm::cross(axis, glm::dvec3(0, 0, 1))
                                   : glm::cross(axis, glm::dvec3(1, 0, 0));
  }
  glm::dvec3 e1 = glm::normalize(start), e2 = glm::cross(axis, e1);
  double az = 2.0 * kPi * i / n + start_deg * kPi / 180.0, el = elevation_deg * kPi / 180.0;
  Camera c = base;
  c.look_at = centre;
  c.position = centre + radius * (std::cos(el) * (std::cos(az) * e1 + std::sin(az) * e2) +
                                  std::sin(el) * axis);
  if (std::abs(std::abs(elevation_deg) - 90.0) < 1e-9) {
    // Looking straight down the axis: the up vector must not be parallel to the view direction.
    c.up = std::cos(az) * e1 + std::sin(az) * e2;
  }
  return c;
}

Rect screenRectOf(const Camera& cam, const Box3& box) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  // Rays sample only t > 0 (a sample at the eye itself, t = 0, has a span of zero length there):
  // a box with no corner in front of the eye plane is never seen.
  const glm::dvec3 f = cam.forward();
  int behind = 0;
  for (int c = 0; c < 8; ++c) behind += glm::dot(box.corner(c) - cam.position, f) <= 0.0;
  if (behind == 8) return {};
  const glm::dvec2 s = cam.screenScale();
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 d = box.corner(c) - cam.position;
    if (!cam.orthographic() && behind > 0)
      return {0, 0, cam.width, cam.height};  // straddles the eye plane: be conservative
    // project() without its eye-plane test: an orthographic corner behind the plane projects
    // where the box's part in front of it may reach.
    const double w = cam.orthographic() ? 1.0 : glm::dot(d, f);
    const double px = (glm::dot(d, cam.right()) / (w * s.x) + 1.0) * 0.5 * cam.width;
    const double py = (1.0 - glm::dot(d, cam.trueUp()) / (w * s.y)) * 0.5 * cam.height;
    x0 = std::min(x0, px), x1 = std::max(x1, px);
    y0 = std::min(y0, py), y1 = std::max(y1, py);
  }
  // A pixel is covered when its centre (+0.5) is inside; pad one pixel for rasteriser rounding.
  // Clamp first: a corner just in front of the eye plane projects to huge coordinates.
  x0 = std::clamp(x0, -2.0, cam.width + 2.0), x1 = std::clamp(x1, -2.0, cam.width + 2.0);
  y0 = std::clamp(y0, -2.0, cam.height + 2.0), y1 = std::clamp(y1, -2.0, cam.height + 2.0);
  int ix0 = std::max(0, int(std::floor(x0)) - 1), iy0 = std::max(0, int(std::floor(y0)) - 1);
  int ix1 = std::min(cam.width, int(std::ceil(x1)) + 1), iy1 = std::min(cam.height, int(std::ceil(y1)) + 1);
  if (ix1 <= ix0 || iy1 <= iy0) return {};
  return {ix0, iy0, ix1 - ix0, iy1 - iy0};
}

Rect unite(const Rect& a, const Rect& b) {
  // Ends in 64 bits: rectangles from a message may hold any int32, and x + w could overflow int.
  // A union wider than int can hold (only from such rectangles) is cut to INT_MAX.
  auto clampInt = [](long long v) { return int(std::min<long long>(v, INT_MAX)); };
  long long x0 = std::min(a.x, b.x), y0 = std::min(a.y, b.y);
  long long x1 = std::max(1LL * a.x + a.w, 1LL * b.x + b.w);
  long long y1 = std::max(1LL * a.y + a.h, 1LL * b.y + b.h);
  return {int(x0), int(y0), clampInt(x1 - x0), clampInt(y1 - y0)};
}

}  // namespace sortlast
