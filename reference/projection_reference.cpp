#include "reference/projection_reference.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <thread>

#include "common/error.h"
#include "transfer/projection_colour.h"

namespace sortlast {

namespace {

// The extremum of the cubic k0 + k1 s + k2 s^2 + k3 s^3 over s in [0, 1].
double cubicExtremum(double k0, double k1, double k2, double k3, bool largest) {
  auto better = [&](double a, double b) { return largest ? std::max(a, b) : std::min(a, b); };
  auto f = [&](double s) { return k0 + s * (k1 + s * (k2 + s * k3)); };
  double best = better(f(0.0), f(1.0));
  const double qa = 3.0 * k3, qb = 2.0 * k2, qc = k1;
  double r[2] = {-1.0, -1.0};
  if (std::abs(qa) <= 1e-14 * (std::abs(qb) + std::abs(qc))) {
    if (qb != 0.0) r[0] = -qc / qb;
  } else {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      r[0] = q / qa;
      if (q != 0.0) r[1] = qc / q;
    }
  }
  for (double s : r)
    if (s > 0.0 && s < 1.0) best = better(best, f(s));
  return best;
}

// The trilinear field of corners c (index x + 2y + 4z) at local l0 + dl s, as a cubic in s.
double cellExtremum(const double c[8], const glm::dvec3& l0, const glm::dvec3& dl, bool largest) {
  const double a = c[0], bx = c[1] - c[0], by = c[2] - c[0], bz = c[4] - c[0];
  const double bxy = c[3] - c[1] - c[2] + c[0], bxz = c[5] - c[1] - c[4] + c[0],
               byz = c[6] - c[2] - c[4] + c[0];
  const double bxyz = c[7] - c[3] - c[5] - c[6] + c[1] + c[2] + c[4] - c[0];
  const double x0 = l0.x, y0 = l0.y, z0 = l0.z, dx = dl.x, dy = dl.y, dz = dl.z;
  const double k0 = a + bx * x0 + by * y0 + bz * z0 + bxy * x0 * y0 + bxz * x0 * z0 + byz * y0 * z0 +
                    bxyz * x0 * y0 * z0;
  const double k1 = bx * dx + by * dy + bz * dz + bxy * (x0 * dy + dx * y0) + bxz * (x0 * dz + dx * z0) +
                    byz * (y0 * dz + dy * z0) + bxyz * (dx * y0 * z0 + x0 * dy * z0 + x0 * y0 * dz);
  const double k2 = bxy * dx * dy + bxz * dx * dz + byz * dy * dz +
                    bxyz * (dx * dy * z0 + dx * y0 * dz + x0 * dy * dz);
  const double k3 = bxyz * dx * dy * dz;
  return cubicExtremum(k0, k1, k2, k3, largest);
}

}  // namespace

double exactExtremum(const WholeVolume& vol, const glm::dvec3& o, const glm::dvec3& d, double t0,
                     double t1, bool largest) {
  const glm::ivec3 n = vol.grid.dims;
  const glm::dvec3 u_o = vol.grid.indexOfWorld(o);
  const glm::dvec3 u_d = vol.grid.indexOfWorld(o + d) - u_o;  // index units per unit t
  double best = std::numeric_limits<double>::quiet_NaN();
  auto sample = [&](int x, int y, int z) {
    return double(vol.samples[size_t(x) + size_t(n.x) * (size_t(y) + size_t(n.y) * size_t(z))]);
  };
  double t = t0;
  for (int guard = 3 * (n.x + n.y + n.z) + 8; t < t1 && guard > 0; --guard) {
    const glm::dvec3 ua = u_o + t * u_d;
    glm::ivec3 cell;
    for (int a = 0; a < 3; ++a) {
      const double nudge = u_d[a] > 0 ? 1e-9 : u_d[a] < 0 ? -1e-9 : 0.0;
      cell[a] = std::clamp(int(std::floor(ua[a] + nudge)), 0, n[a] - 2);
    }
    double tb = t1;
    for (int a = 0; a < 3; ++a) {
      if (std::abs(u_d[a]) < 1e-300) continue;
      const double plane = cell[a] + (u_d[a] > 0 ? 1 : 0);
      const double te = (plane - u_o[a]) / u_d[a];
      if (te > t) tb = std::min(tb, te);
    }
    if (!(tb > t)) tb = std::min(t1, t + 1e-9 / std::max(glm::length(u_d), 1e-300));
    double c[8];
    bool missing = false;
    for (int i = 0; i < 8; ++i) {
      c[i] = sample(cell.x + (i & 1), cell.y + ((i >> 1) & 1), cell.z + ((i >> 2) & 1));
      missing = missing || std::isnan(c[i]);
    }
    if (!missing) {
      const glm::dvec3 l0 = glm::clamp(ua - glm::dvec3(cell), 0.0, 1.0);
      const glm::dvec3 l1 = glm::clamp(u_o + tb * u_d - glm::dvec3(cell), 0.0, 1.0);
      const double e = cellExtremum(c, l0, l1 - l0, largest);
      best = std::isnan(best) ? e : largest ? std::max(best, e) : std::min(best, e);
    }
    t = tb;
  }
  return best;
}

ImageF projectReference(const WholeVolume& vol, const TransferFunction& tf, const Camera& cam,
                        double step, int threads, VolumeBlend blend, bool exact, const SurfaceImage* stop) {
  ImageF img(cam.width, cam.height);
  const Box3 box = vol.grid.worldBox();
  const bool largest = blend == VolumeBlend::kMip;
  std::atomic<int> next_row{0};
  auto worker = [&] {
    for (int y; (y = next_row++) < cam.height;)
      for (int x = 0; x < cam.width; ++x) {
        const CameraRay ray = cam.pixelRay(x, y);  // from the eye, or the eye plane (orthographic)
        const glm::dvec3 o = ray.origin, d = ray.direction;
        double t0, t1;
        if (!intersectRayBox(o, d, box, t0, t1)) continue;
        t0 = std::max(t0, 0.0);
        clipSpan(vol.clip, o, d, t0, t1);  // clip.planes, clip.box (common/clip.h)
        const size_t pixel = size_t(y) * cam.width + x;
        if (stop && stop->hit(pixel)) t1 = std::min(t1, double(stop->t[pixel]));  // the first opaque hit
        if (!(t1 > t0)) continue;
        float* p = &img.px[(size_t(y) * cam.width + x) * 4];
        if (exact && !vol.adaptive) {
          const double v = exactExtremum(vol, o, d, t0, t1, largest);
          if (!std::isnan(v)) p[0] = float(v), p[3] = 1.0f;
          continue;
        }
        const long long n = std::max(1LL, (long long)std::ceil((t1 - t0) / step));
        const double h = (t1 - t0) / double(n);
        double acc = 0.0, count = 0.0, rgb[3] = {0, 0, 0}, alpha = 0.0;
        for (long long i = 0; i < n; ++i) {
          const double v = vol.at(vol.grid.indexOfWorld(o + (t0 + (i + 0.5) * h) * d));
          if (std::isnan(v)) continue;
          if (blend == VolumeBlend::kAdditive) {
            const double a = 1.0 - std::exp(-tf.extinction(v) * h);
            const auto c = tf.colour(v);
            for (int k = 0; k < 3; ++k) rgb[k] += c[k] * a;
            alpha += a;
            continue;
          }
          if (blend == VolumeBlend::kAverage) acc += v;
          else if (count == 0.0) acc = v;
          else acc = largest ? std::max(acc, v) : std::min(acc, v);
          count += 1.0;
        }
        if (blend == VolumeBlend::kAdditive) {
          for (int k = 0; k < 3; ++k) p[k] = float(rgb[k]);
          p[3] = float(alpha);
        } else if (count > 0.0) {
          p[0] = float(blend == VolumeBlend::kAverage ? acc / count : acc);
          p[3] = 1.0f;
        }
      }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(1, threads); ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  return img;
}

ImageF renderProjectionReference(const WholeVolume& vol, const TransferFunction& tf, const Camera& cam,
                                 double step, int threads, VolumeBlend blend, bool exact,
                                 const SurfaceImage* stop, const ImageF* stop_colour) {
  if (stop && (stop->width != cam.width || stop->height != cam.height || !stop_colour ||
               stop_colour->width != cam.width || stop_colour->height != cam.height))
    throw InputError("projection reference: the surface images are not the camera's size (" +
                     std::to_string(cam.width) + "x" + std::to_string(cam.height) + ")");
  ImageF img = projectReference(vol, tf, cam, step, threads, blend, exact, stop);
  for (size_t i = 0; i < img.px.size(); i += 4) {
    float* p = &img.px[i];
    if (blend == VolumeBlend::kAdditive) {
      clampAdditive(p);
    } else if (p[3] > 0.0f) {
      const auto c = projectedColour(tf, double(p[0]));  // in double, of the float value
      for (int k = 0; k < 4; ++k) p[k] = float(c[k]);
    }
    if (stop && stop->hit(i / 4)) {  // the projection's colour over the opaque layer's
      const float* s = &stop_colour->px[i];
      const double t = 1.0 - double(p[3]);
      for (int k = 0; k < 4; ++k) p[k] = float(double(p[k]) + t * double(s[k]));
    }
  }
  return img;
}

}  // namespace sortlast
