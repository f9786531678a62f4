#include "reference/isosurface_reference.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "common/box.h"
#include "common/clip.h"
#include "common/error.h"

namespace sortlast {

namespace {

using Cubic = std::array<double, 4>;  // c[0] + c[1] s + c[2] s^2 + c[3] s^3

double eval(const Cubic& c, double s) { return ((c[3] * s + c[2]) * s + c[1]) * s + c[0]; }

// The corner values of cell `c` (its lowest corner), x fastest: v[dx + 2 dy + 4 dz].
std::array<double, 8> cornersOf(const WholeVolume& vol, const glm::ivec3& c) {
  const glm::ivec3 n = vol.grid.dims;
  std::array<double, 8> v;
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 p = c + glm::ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    v[size_t(k)] = double(vol.samples[size_t(p.x) + size_t(n.x) * (size_t(p.y) + size_t(n.y) * size_t(p.z))]);
  }
  return v;
}

// The trilinear interpolant of corners v along local position f(s) = f0 + df s, as a cubic in s.
Cubic cubicAlong(const std::array<double, 8>& v, const glm::dvec3& f0, const glm::dvec3& df) {
  Cubic out{0, 0, 0, 0};
  for (int k = 0; k < 8; ++k) {
    // The product of the three linear weights: w_a(s) = (1 - f0_a) - df_a s or f0_a + df_a s.
    double p[4] = {1, 0, 0, 0};
    for (int a = 0; a < 3; ++a) {
      const bool hi = (k >> a) & 1;
      const double w0 = hi ? f0[a] : 1.0 - f0[a], w1 = hi ? df[a] : -df[a];
      for (int j = 3; j >= 0; --j) p[j] = p[j] * w0 + (j > 0 ? p[j - 1] * w1 : 0.0);
    }
    for (int j = 0; j < 4; ++j) out[size_t(j)] += v[size_t(k)] * p[j];
  }
  return out;
}

// The derivative of the trilinear interpolant of corners v at local f, per index unit.
glm::dvec3 trilinearGradient(const std::array<double, 8>& v, const glm::dvec3& f) {
  auto c = [&](int x, int y, int z) { return v[size_t(x + 2 * y + 4 * z)]; };
  glm::dvec3 g;
  g.x = (1 - f.y) * (1 - f.z) * (c(1, 0, 0) - c(0, 0, 0)) + f.y * (1 - f.z) * (c(1, 1, 0) - c(0, 1, 0)) +
        (1 - f.y) * f.z * (c(1, 0, 1) - c(0, 0, 1)) + f.y * f.z * (c(1, 1, 1) - c(0, 1, 1));
  g.y = (1 - f.x) * (1 - f.z) * (c(0, 1, 0) - c(0, 0, 0)) + f.x * (1 - f.z) * (c(1, 1, 0) - c(1, 0, 0)) +
        (1 - f.x) * f.z * (c(0, 1, 1) - c(0, 0, 1)) + f.x * f.z * (c(1, 1, 1) - c(1, 0, 1));
  g.z = (1 - f.x) * (1 - f.y) * (c(0, 0, 1) - c(0, 0, 0)) + f.x * (1 - f.y) * (c(1, 0, 1) - c(1, 0, 0)) +
        (1 - f.x) * f.y * (c(0, 1, 1) - c(0, 1, 0)) + f.x * f.y * (c(1, 1, 1) - c(1, 1, 0));
  return g;
}

// The roots of the cubic's derivative inside (0, len), sorted.
std::vector<double> turningPoints(const Cubic& c, double len) {
  const double a = 3 * c[3], b = 2 * c[2], k = c[1];
  std::vector<double> r;
  const double scale = std::abs(a) + std::abs(b) + std::abs(k);
  if (scale == 0.0) return r;
  if (std::abs(a) <= 1e-14 * scale) {
    if (b != 0.0) r.push_back(-k / b);
  } else {
    const double disc = b * b - 4 * a * k;
    if (disc >= 0.0) {
      // The stable pair: q = -(b + sign(b) sqrt(disc)) / 2, roots q / a and k / q.
      const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      r.push_back(q / a);
      if (q != 0.0) r.push_back(k / q);
    }
  }
  std::vector<double> in;
  for (double s : r)
    if (s > 0.0 && s < len) in.push_back(s);
  std::sort(in.begin(), in.end());
  return in;
}

}  // namespace

std::vector<IsoHit> isoCrossings(const WholeVolume& vol, const std::vector<Isovalue>& isovalues,
                                 const glm::dvec3& o, const glm::dvec3& d, double ta, double tb) {
  if (vol.adaptive) throw std::logic_error("isosurface reference: not for adaptive fields");
  std::vector<IsoHit> hits;
  if (!(tb > ta) || isovalues.empty()) return hits;
  const GridGeometry& g = vol.grid;
  const glm::ivec3 n = g.dims;
  const glm::dvec3 u0 = g.indexOfWorld(o), du = d / g.spacing;  // u(t) = u0 + t du
  // Every t in (ta, tb) where the ray crosses a cell face.
  std::vector<double> cuts{ta, tb};
  for (int a = 0; a < 3; ++a) {
    if (du[a] == 0.0) continue;
    const double ua = u0[a] + ta * du[a], ub = u0[a] + tb * du[a];
    for (double k = std::ceil(std::min(ua, ub)); k <= std::floor(std::max(ua, ub)); k += 1.0) {
      const double t = (k - u0[a]) / du[a];
      if (t > ta && t < tb) cuts.push_back(t);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  const size_t m = isovalues.size();
  std::vector<char> above(m, 0);
  bool first = true;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double t_lo = cuts[i], len = cuts[i + 1] - t_lo;
    if (!(len > 0.0)) continue;
    const glm::dvec3 mid = u0 + (t_lo + 0.5 * len) * du;
    glm::ivec3 c;
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(int(std::floor(mid[a])), 0, n[a] - 2);
    const std::array<double, 8> v = cornersOf(vol, c);
    const glm::dvec3 f0 = u0 + t_lo * du - glm::dvec3(c);
    const Cubic cubic = cubicAlong(v, f0, du);
    if (first) {
      for (size_t j = 0; j < m; ++j) above[j] = eval(cubic, 0.0) >= isovalues[j].value;
      first = false;
    }
    std::vector<double> ends = turningPoints(cubic, len);
    ends.push_back(len);
    // This cell's hits, of every isovalue, sorted afterwards.
    std::vector<IsoHit> cell;
    for (size_t j = 0; j < m; ++j) {
      const double iso = isovalues[j].value;
      double s_a = 0.0;
      for (double s_b : ends) {
        const bool ab = eval(cubic, s_b) >= iso;
        if (ab != bool(above[j])) {
          // Bisect on the piece [s_a, s_b]: lo keeps the old side, hi the new.
          double lo = s_a, hi = s_b;
          for (int it = 0; it < 200; ++it) {
            const double s = 0.5 * (lo + hi);
            if (s <= lo || s >= hi) break;
            ((eval(cubic, s) >= iso) == bool(above[j]) ? lo : hi) = s;
          }
          const double s = 0.5 * (lo + hi);
          const glm::dvec3 f = f0 + s * du;
          cell.push_back({t_lo + s, trilinearGradient(v, f) / g.spacing, int(j)});
          above[j] = ab;
        }
        s_a = s_b;
      }
    }
    std::sort(cell.begin(), cell.end(), [](const IsoHit& x, const IsoHit& y) { return x.t < y.t; });
    for (const IsoHit& h : cell) {
      hits.push_back(h);
      if (isovalues[size_t(h.iso)].opacity >= 1.0) return hits;
    }
  }
  return hits;
}

ImageF renderIsosurfaceReference(const WholeVolume& vol, const std::vector<Isovalue>& isovalues,
                                 const Shading& shading, const Camera& cam, int threads,
                                 const SurfaceImage* stop, const ImageF* stop_colour,
                                 SurfaceImage* opaque) {
  if (stop && (stop->width != cam.width || stop->height != cam.height || !stop_colour ||
               stop_colour->width != cam.width || stop_colour->height != cam.height))
    throw InputError("isosurface reference: the surface images are not the camera's size (" +
                     std::to_string(cam.width) + "x" + std::to_string(cam.height) + ")");
  ImageF img(cam.width, cam.height);
  if (opaque) *opaque = SurfaceImage(cam.width, cam.height);
  const Box3 box = vol.grid.worldBox();
  std::atomic<int> next_row{0};
  auto worker = [&] {
    for (int y; (y = next_row++) < cam.height;) {
      for (int x = 0; x < cam.width; ++x) {
        const size_t pixel = size_t(y) * cam.width + x;
        const CameraRay ray = cam.pixelRay(x, y);  // from the eye, or the eye plane (orthographic)
        const glm::dvec3 o = ray.origin, d = ray.direction;
        const bool hit_surface = stop && stop->hit(pixel);
        glm::dvec3 rgb(0.0);
        double transmit = 1.0;
        double t0, t1;
        if (intersectRayBox(o, d, box, t0, t1)) {
          t0 = std::max(t0, 0.0);
          // The clip region (common/clip.h) cuts the span the crossings are searched in: a
          // crossing counts only inside it (the field's side at the cut is where the search starts).
          clipSpan(vol.clip, o, d, t0, t1);
          if (hit_surface) t1 = std::min(t1, double(stop->t[pixel]));
          for (const IsoHit& h : isoCrossings(vol, isovalues, o, d, t0, t1)) {
            const Isovalue& iso = isovalues[size_t(h.iso)];
            rgb += transmit * iso.opacity * shadeIsoHit(iso.colour, h.gradient, d, shading);
            transmit *= 1.0 - iso.opacity;
            if (opaque && iso.opacity >= 1.0) {  // the last hit
              const double len = glm::length(h.gradient);
              opaque->t[pixel] = float(h.t);
              opaque->normal[pixel] = len > 0.0 ? glm::vec3(-h.gradient / len) : glm::vec3(0.0f);
            }
          }
        }
        double alpha = 1.0 - transmit;
        if (hit_surface) {
          const float* s = &stop_colour->px[4 * pixel];
          for (int k = 0; k < 3; ++k) rgb[k] += transmit * s[k];
          alpha = 1.0 - transmit * (1.0 - s[3]);
        }
        float* p = &img.px[pixel * 4];
        for (int k = 0; k < 3; ++k) p[k] = float(rgb[k]);
        p[3] = float(alpha);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(1, threads); ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  return img;
}

}  // namespace sortlast
