#include "reference/surface_reference.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace sortlast {

namespace {

struct Hit {
  double t = HUGE_VAL;
  int entry = -1, face = -1;
  double u = 0, v = 0;
};

// Moller-Trumbore: t and barycentrics (b1 towards b, b2 towards c) of the ray's hit, or false.
bool intersect(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
               const glm::dvec3& c, double& t, double& b1, double& b2) {
  const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-300) return false;
  const double inv = 1.0 / det;
  const glm::dvec3 s = o - a;
  b1 = glm::dot(s, p) * inv;
  if (b1 < 0.0 || b1 > 1.0) return false;
  const glm::dvec3 q = glm::cross(s, e1);
  b2 = glm::dot(d, q) * inv;
  if (b2 < 0.0 || b1 + b2 > 1.0) return false;
  t = glm::dot(e2, q) * inv;
  return t > 0.0;
}

}  // namespace

SurfaceReference::SurfaceReference(const std::vector<SurfaceSpec>& surfaces, int tessellation) : n_(tessellation) {
  for (const SurfaceSpec& s : surfaces) {
    Entry e{SubdivSurface(*s.mesh), s.shading, {}, 1.0, {}};
    const PolyMesh& cm = e.surface.control().mesh;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : cm.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    e.centre = 0.5 * (lo + hi);  // as the GL renderer takes them
    e.size = cm.size();
    const int m = n_ + 1;
    e.grid.resize(size_t(cm.faceCount()) * m * m);
    for (int f = 0; f < cm.faceCount(); ++f)
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i)
          e.grid[(size_t(f) * m + j) * m + i] = e.surface.evaluate(f, double(i) / n_, double(j) / n_).position;
    entries_.push_back(std::move(e));
  }
}

void SurfaceReference::render(const Camera& cam, int threads, SurfaceImage& surface, ImageF& colour,
                              SurfaceReferenceStats* stats) const {
  const int W = cam.width, H = cam.height, m = n_ + 1;
  std::vector<Hit> hits(size_t(W) * H);
  // Rows [y0, y1): every triangle whose projection meets them, nearest hit per pixel.
  auto rasterise = [&](int y0, int y1) {
    for (int k = 0; k < int(entries_.size()); ++k) {
      const Entry& e = entries_[size_t(k)];
      const int faces = e.surface.control().mesh.faceCount();
      const bool open = e.surface.twoSided();
      for (int f = 0; f < faces; ++f)
        for (int j = 0; j < n_ && !e.surface.hole(f); ++j)
          for (int i = 0; i < n_; ++i) {
            const size_t base = size_t(f) * m * m;
            const glm::dvec3 p[4] = {e.grid[base + size_t(j) * m + i], e.grid[base + size_t(j) * m + i + 1],
                                     e.grid[base + size_t(j + 1) * m + i + 1], e.grid[base + size_t(j + 1) * m + i]};
            const double pu[4] = {double(i), double(i + 1), double(i + 1), double(i)};
            const double pv[4] = {double(j), double(j), double(j + 1), double(j + 1)};
            double x0 = 1e300, x1 = -1e300, yy0 = 1e300, yy1 = -1e300;
            bool behind = false;
            for (const glm::dvec3& q : p) {
              auto s = cam.project(q);
              if (!s) { behind = true; break; }
              x0 = std::min(x0, s->x), x1 = std::max(x1, s->x), yy0 = std::min(yy0, s->y), yy1 = std::max(yy1, s->y);
            }
            // Pixel centres at +0.5, one pixel of margin for rounding.
            const int ix0 = behind ? 0 : std::max(0, int(std::floor(x0 - 1.5)));
            const int ix1 = behind ? W - 1 : std::min(W - 1, int(std::ceil(x1 + 0.5)));
            const int iy0 = std::max(y0, behind ? 0 : int(std::floor(yy0 - 1.5)));
            const int iy1 = std::min(y1 - 1, behind ? H - 1 : int(std::ceil(yy1 + 0.5)));
            for (int y = iy0; y <= iy1; ++y)
              for (int x = ix0; x <= ix1; ++x) {
                const CameraRay ray = cam.pixelRay(x, y);  // from the eye, or the eye plane
                const glm::dvec3 d = ray.direction;
                Hit& h = hits[size_t(y) * W + x];
                for (int tri = 0; tri < 2; ++tri) {
                  const int a = 0, b = tri == 0 ? 1 : 2, c = tri == 0 ? 2 : 3;
                  // Back faces skipped on closed surfaces, as the GL pass culls them there (they
                  // are hidden anyway); an open surface is two-sided.
                  if (!open && glm::dot(glm::cross(p[b] - p[a], p[c] - p[a]), d) >= 0) continue;
                  double t, b1, b2;
                  if (!intersect(ray.origin, d, p[a], p[b], p[c], t, b1, b2) || t >= h.t) continue;
                  const double w0 = 1.0 - b1 - b2;
                  h = {t, k, f, (w0 * pu[a] + b1 * pu[b] + b2 * pu[c]) / n_, (w0 * pv[a] + b1 * pv[b] + b2 * pv[c]) / n_};
                }
              }
          }
    }
  };
  // Then Newton on the exact surface per hit pixel, and shading.
  surface = SurfaceImage(W, H);
  colour = ImageF(W, H);
  std::vector<double> residual(size_t(H), 0.0);
  std::vector<long long> edge(size_t(H), 0), count(size_t(H), 0);
  auto refine = [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < W; ++x) {
        const size_t px = size_t(y) * W + x;
        Hit h = hits[px];
        if (h.entry < 0) continue;
        const Entry& e = entries_[size_t(h.entry)];
        const CameraRay ray = cam.pixelRay(x, y);  // from the eye, or the eye plane (orthographic)
        const glm::dvec3 o = ray.origin, d = ray.direction;
        double u = h.u, v = h.v, t = h.t;
        bool clamped = false;
        const double du = 1e-6;
        for (int it = 0; it < 16; ++it) {
          const glm::dvec3 s = e.surface.evaluate(h.face, u, v).position;
          const glm::dvec3 F = s - o - t * d;
          if (glm::length(F) < 1e-13 * e.size) {
            clamped = false;  // on the ray, wherever the steps went
            break;
          }
          // Central differences inside [0, 1] (one-sided at the face's edges).
          const double ua = std::max(0.0, u - du), ub = std::min(1.0, u + du);
          const double va = std::max(0.0, v - du), vb = std::min(1.0, v + du);
          const glm::dvec3 su = (e.surface.evaluate(h.face, ub, v).position - e.surface.evaluate(h.face, ua, v).position) / (ub - ua);
          const glm::dvec3 sv = (e.surface.evaluate(h.face, u, vb).position - e.surface.evaluate(h.face, u, va).position) / (vb - va);
          const glm::dmat3 J(su, sv, -d);  // columns: d/du, d/dv, d/dt
          if (std::abs(glm::determinant(J)) < 1e-300) break;
          const glm::dvec3 step = glm::inverse(J) * F;
          double nu = u - step.x, nv = v - step.y;
          const double out_by = std::max({-nu, nu - 1.0, -nv, nv - 1.0});
          if (out_by > 0.0) {
            // Across the edge it leaves by most: the same (u, v) in the neighbour's frame. Edge c
            // runs from corner c; (a, b) = along it from corner c, into the face.
            const int c = -nv >= out_by ? 0 : (nu - 1.0 >= out_by ? 1 : (nv - 1.0 >= out_by ? 2 : 3));
            const double a = c == 0 ? nu : c == 1 ? nv : c == 2 ? 1.0 - nu : 1.0 - nv;
            const double b = c == 0 ? nv : c == 1 ? 1.0 - nu : c == 2 ? 1.0 - nv : nu;
            const ControlMesh& cm = e.surface.control();
            const auto& twin = cm.topology.twin[size_t(cm.mesh.face_offsets[h.face] + c)];
            // Across a boundary edge or into a hole there is no surface: stay, clamped.
            if (twin.face >= 0 && !e.surface.hole(twin.face)) {
              const double ga = 1.0 - a, gb = -b;  // the neighbour's edge runs the other way
              const int d = twin.corner;
              nu = d == 0 ? ga : d == 1 ? 1.0 - gb : d == 2 ? 1.0 - ga : gb;
              nv = d == 0 ? gb : d == 1 ? ga : d == 2 ? 1.0 - gb : 1.0 - ga;
              h.face = twin.face;
            }
          }
          clamped = nu < 0 || nu > 1 || nv < 0 || nv > 1;
          u = std::clamp(nu, 0.0, 1.0);
          v = std::clamp(nv, 0.0, 1.0);
          t -= step.z;
        }
        const LimitPoint lp = e.surface.evaluate(h.face, u, v);
        // Distance of the limit point from the ray.
        const glm::dvec3 w = lp.position - o;
        residual[size_t(y)] = std::max(residual[size_t(y)], glm::length(w - glm::dot(w, d) * d));
        edge[size_t(y)] += clamped;
        count[size_t(y)] += 1;
        surface.t[px] = float(glm::length(w));
        surface.normal[px] = glm::vec3(lp.normal);
        const glm::dvec3 rgb = shadeLimitPoint(e.shading, e.centre, e.size, o, lp.position, lp.normal);
        for (int c = 0; c < 3; ++c) colour.px[4 * px + c] = float(rgb[c]);
        colour.px[4 * px + 3] = 1.0f;
      }
  };
  const int T = std::max(1, std::min(threads, H));
  auto inBands = [&](auto& job) {
    std::vector<std::thread> pool;
    for (int i = 0; i < T; ++i) pool.emplace_back([&, i] { job(H * i / T, H * (i + 1) / T); });
    for (auto& th : pool) th.join();
  };
  inBands(rasterise);
  inBands(refine);
  if (stats) {
    *stats = {};
    for (int y = 0; y < H; ++y) {
      stats->hits += count[size_t(y)];
      stats->worst_residual = std::max(stats->worst_residual, residual[size_t(y)]);
      stats->stopped_at_edge += edge[size_t(y)];
    }
  }
}

void mergeNearest(SurfaceImage& into, ImageF& into_colour, const SurfaceImage& other, const ImageF& other_colour) {
  if (into.t.size() != other.t.size() || into_colour.px.size() != other_colour.px.size())
    throw std::logic_error("mergeNearest: images of different sizes");
  for (size_t i = 0; i < into.t.size(); ++i) {
    if (!other.hit(i) || (into.hit(i) && into.t[i] <= other.t[i])) continue;
    into.t[i] = other.t[i];
    into.normal[i] = other.normal[i];
    for (int c = 0; c < 4; ++c) into_colour.px[4 * i + c] = other_colour.px[4 * i + c];
  }
}

}  // namespace sortlast
