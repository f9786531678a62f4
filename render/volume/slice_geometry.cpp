#include "render/volume/slice_geometry.h"

#include <algorithm>
#include <cmath>

namespace sortlast {

std::vector<float> sliceTriangles(const Box3& box, const glm::dvec3& eye, const glm::dvec3& f,
                                  double spacing, double min_t) {
  double dist[8], tmin = 1e300, tmax = -1e300;
  glm::dvec3 corner[8];
  for (int c = 0; c < 8; ++c) {
    corner[c] = box.corner(c);
    dist[c] = glm::dot(f, corner[c] - eye);
    tmin = std::min(tmin, dist[c]);
    tmax = std::max(tmax, dist[c]);
  }
  // A basis of the slice plane, to order each polygon's vertices by angle.
  glm::dvec3 u = std::abs(f.x) < 0.9 ? glm::cross(f, glm::dvec3(1, 0, 0)) : glm::cross(f, glm::dvec3(0, 1, 0));
  u = glm::normalize(u);
  glm::dvec3 v = glm::cross(f, u);

  std::vector<float> tris;
  // Planes strictly beyond min_t (a plane exactly at min_t is left out), and none before tmin.
  long long k0 = std::max((long long)std::ceil(tmin / spacing),
                          (long long)std::floor(min_t / spacing) + 1);
  long long k1 = (long long)std::floor(tmax / spacing);
  if (std::max(tmin, min_t) > tmax) return tris;
  std::vector<glm::dvec3> poly;
  std::vector<std::pair<double, glm::dvec3>> sorted;
  for (long long k = k1; k >= k0; --k) {
    double t = double(k) * spacing;
    poly.clear();
    // The 12 edges, each from the corner with the lower coordinate to the higher one, so a face
    // shared by two bricks yields bit-identical intersection points in both.
    for (int a = 0; a < 8; ++a)
      for (int bit = 1; bit < 8; bit <<= 1) {
        if (a & bit) continue;
        int b = a | bit;
        double sa = dist[a] - t, sb = dist[b] - t;
        // A corner exactly on the plane counts as being behind it (s <= 0), so a plane through a
        // face gives that face's polygon to exactly one of the two bricks sharing it.
        if ((sa <= 0.0) == (sb <= 0.0)) continue;
        poly.push_back(corner[a] + (corner[b] - corner[a]) * (sa / (sa - sb)));
      }
    if (poly.size() < 3) continue;
    glm::dvec3 c(0.0);
    for (auto& p : poly) c += p;
    c /= double(poly.size());
    sorted.clear();
    for (auto& p : poly) sorted.push_back({std::atan2(glm::dot(p - c, v), glm::dot(p - c, u)), p});
    std::sort(sorted.begin(), sorted.end(), [](auto& x, auto& y) { return x.first < y.first; });
    for (size_t i = 1; i + 1 < sorted.size(); ++i)
      for (const glm::dvec3* p : {&sorted[0].second, &sorted[i].second, &sorted[i + 1].second}) {
        tris.push_back(float(p->x));
        tris.push_back(float(p->y));
        tris.push_back(float(p->z));
      }
  }
  return tris;
}

}  // namespace sortlast
