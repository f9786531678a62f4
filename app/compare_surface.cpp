#include "app/compare_surface.h"

#include <cmath>
#include <string>

#include "common/error.h"

namespace sortlast {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Angle in degrees, through atan2 rather than acos: acos loses all precision near 0 degrees,
// which is exactly where a good renderer's normals are.
double angleDeg(const glm::vec3& a, const glm::vec3& b) {
  glm::dvec3 u(a), v(b);
  double lu = glm::length(u), lv = glm::length(v);
  if (!(lu > 0.0 && lv > 0.0 && std::isfinite(lu) && std::isfinite(lv))) return 180.0;
  u /= lu, v /= lv;
  return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v)) * 180.0 / kPi;
}

}  // namespace

bool isSilhouettePixel(const SurfaceImage& ref, int x, int y) {
  bool centre = ref.hit(size_t(y) * ref.width + x);
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    int nx = x + dx[k], ny = y + dy[k];
    if (nx < 0 || ny < 0 || nx >= ref.width || ny >= ref.height) continue;
    if (ref.hit(size_t(ny) * ref.width + nx) != centre) return true;
  }
  return false;
}

SurfaceDifference compareSurfaces(const SurfaceImage& ref, const SurfaceImage& test,
                                  bool ignore_edges, double depth_tolerance, double crease_deg,
                                  const std::vector<uint8_t>* ignore) {
  auto onCrease = [&](int x, int y) {
    const size_t i = size_t(y) * ref.width + x;
    if (!ref.hit(i)) return false;
    const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int nx = x + dx[k], ny = y + dy[k];
      if (nx < 0 || ny < 0 || nx >= ref.width || ny >= ref.height) continue;
      const size_t j = size_t(ny) * ref.width + nx;
      if (ref.hit(j) && angleDeg(ref.normal[i], ref.normal[j]) > crease_deg) return true;
    }
    return false;
  };
  if (ref.width != test.width || ref.height != test.height)
    throw InputError("compare-surface: image sizes differ (" + std::to_string(ref.width) + "x" +
                     std::to_string(ref.height) + " vs " + std::to_string(test.width) + "x" +
                     std::to_string(test.height) + ")");
  SurfaceDifference d;
  double depth_sq = 0.0, normal_sum = 0.0;
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) {
      size_t i = size_t(y) * ref.width + x;
      if ((ignore_edges && isSilhouettePixel(ref, x, y)) || (ignore && (*ignore)[i])) {
        ++d.edges_ignored;
        continue;
      }
      if (std::isfinite(crease_deg) && onCrease(x, y)) {
        ++d.creases_ignored;
        continue;
      }
      bool r = ref.hit(i), t = test.hit(i);
      if (r && !t) {
        if (d.holes++ == 0) d.first_hole_x = x, d.first_hole_y = y;
      } else if (!r && t) {
        if (d.extra++ == 0) d.first_extra_x = x, d.first_extra_y = y;
      } else if (r && t) {
        ++d.both;
        double e = std::abs(double(ref.t[i]) - double(test.t[i]));
        depth_sq += e * e;
        if (e > depth_tolerance) ++d.depth_outliers;
        if (e > d.depth_max || d.worst_depth_x < 0)
          d.depth_max = e, d.worst_depth_x = x, d.worst_depth_y = y;
        double a = angleDeg(ref.normal[i], test.normal[i]);
        normal_sum += a;
        if (a > d.normal_max_deg || d.worst_normal_x < 0)
          d.normal_max_deg = a, d.worst_normal_x = x, d.worst_normal_y = y;
      }
    }
  if (d.both > 0) {
    d.depth_rms = std::sqrt(depth_sq / double(d.both));
    d.normal_mean_deg = normal_sum / double(d.both);
  }
  return d;
}

}  // namespace sortlast
