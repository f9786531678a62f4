#include "reference/surface_roughness.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.h"

namespace sortlast {

namespace {

// Whether two pixels both hit and their depths are continuous (RoughnessOptions::max_depth_jump).
bool continuous(const SurfaceImage& img, const RoughnessOptions& o, size_t p, size_t q) {
  if (!img.hit(p) || !img.hit(q)) return false;
  double tp = img.t[p], tq = img.t[q];
  return std::abs(tp - tq) <= o.max_depth_jump * std::min(tp, tq);
}

// Union-find over the region's pixels: continuous hit neighbours join one piece.
long long countPieces(const SurfaceImage& img, const RoughnessOptions& o, int x1, int y1) {
  const int w = x1 - o.x0, h = y1 - o.y0;
  std::vector<int> parent(size_t(w) * h);
  for (size_t i = 0; i < parent.size(); ++i) parent[i] = int(i);
  auto find = [&](int a) {
    while (parent[size_t(a)] != a) a = parent[size_t(a)] = parent[size_t(parent[size_t(a)])];
    return a;
  };
  auto at = [&](int x, int y) { return size_t(y) * img.width + size_t(x); };
  auto joined = [&](size_t p, size_t q) { return continuous(img, o, p, q); };
  for (int y = o.y0; y < y1; ++y)
    for (int x = o.x0; x < x1; ++x) {
      const int here = (y - o.y0) * w + (x - o.x0);
      if (x + 1 < x1 && joined(at(x, y), at(x + 1, y))) parent[size_t(find(here))] = find(here + 1);
      if (y + 1 < y1 && joined(at(x, y), at(x, y + 1))) parent[size_t(find(here))] = find(here + w);
    }
  std::vector<int> size(parent.size(), 0);
  for (int y = o.y0; y < y1; ++y)
    for (int x = o.x0; x < x1; ++x)
      if (img.hit(at(x, y))) ++size[size_t(find((y - o.y0) * w + (x - o.x0)))];
  long long pieces = 0;
  for (int s : size) pieces += s >= std::max(1, o.min_piece_pixels);
  return pieces;
}

}  // namespace

Roughness surfaceRoughness(const SurfaceImage& img, const RoughnessOptions& o) {
  const int x1 = o.x1 > 0 ? std::min(o.x1, img.width) : img.width;
  const int y1 = o.y1 > 0 ? std::min(o.y1, img.height) : img.height;
  if (!(o.max_depth_jump > 0.0))
    throw InputError("roughness: --max-depth-jump must be > 0");
  if (o.x0 < 0 || o.y0 < 0 || o.x0 >= x1 || o.y0 >= y1)
    throw InputError("roughness: the region [" + std::to_string(o.x0) + ", " + std::to_string(x1) +
                     ") x [" + std::to_string(o.y0) + ", " + std::to_string(y1) +
                     ") is empty or outside the " + std::to_string(img.width) + " x " +
                     std::to_string(img.height) + " image");
  std::vector<double> angles;
  auto pair = [&](size_t p, size_t q) {
    if (!continuous(img, o, p, q)) return;
    glm::dvec3 a(img.normal[p]), b(img.normal[q]);
    double la = glm::length(a), lb = glm::length(b);
    if (!(la > 0.0 && lb > 0.0)) return;
    // atan2 of |a x b| and a.b: accurate for tiny angles too, where acos loses them.
    double angle = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
    angles.push_back(angle * 180.0 / 3.14159265358979323846);
  };
  for (int y = o.y0; y < y1; ++y)
    for (int x = o.x0; x < x1; ++x) {
      size_t i = size_t(y) * img.width + x;
      if (x + 1 < x1) pair(i, i + 1);
      if (y + 1 < y1) pair(i, i + size_t(img.width));
    }
  Roughness r;
  r.t_min = INFINITY, r.t_max = -INFINITY;
  for (int y = o.y0; y < y1; ++y)
    for (int x = o.x0; x < x1; ++x) {
      size_t i = size_t(y) * img.width + x;
      if (img.hit(i)) r.t_min = std::min(r.t_min, double(img.t[i])), r.t_max = std::max(r.t_max, double(img.t[i]));
    }
  r.pieces = countPieces(img, o, x1, y1);
  r.t_centre = img.t[size_t((o.y0 + y1) / 2) * img.width + size_t((o.x0 + x1) / 2)];
  r.pairs = (long long)angles.size();
  if (angles.empty()) return r;
  double sum = 0.0, sum2 = 0.0;
  for (double a : angles) sum += a, sum2 += a * a;
  r.mean_deg = sum / double(angles.size());
  r.rms_deg = std::sqrt(sum2 / double(angles.size()));
  size_t k = std::min(angles.size() - 1, size_t(0.95 * double(angles.size())));
  std::nth_element(angles.begin(), angles.begin() + long(k), angles.end());
  r.p95_deg = angles[k];
  return r;
}

}  // namespace sortlast
