// The anisotropic kernels of io/anisotropic_kernels.h: a cell-grid neighbour search, then per
// particle the density, radius, weighted mean and covariance, and the ellipsoid from Eigen's
// symmetric 3x3 eigen-decomposition.
#include "io/anisotropic_kernels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include <Eigen/Eigenvalues>

#include "common/error.h"
#include "common/pixel_threads.h"

namespace sortlast {

namespace {

constexpr double kDirectionFade = 0.1;

double smoothstep(double t, double lo, double hi) {
  if (t <= lo) return 0.0;
  if (t >= hi) return 1.0;
  double x = (t - lo) / (hi - lo);
  return x * x * (3.0 - 2.0 * x);
}

// Particles binned by cells of edge >= h_n / 2 over their bounds: every neighbour within h_n of a
// particle lies in the 5 x 5 x 5 cells around its own, and only those whose box comes within h_n
// are read (about 3x fewer candidates than cells of h_n and their 26 neighbours: measured 6.1 ->
// s per million on the procedural splash). Lists ascend (counting sort in order).
struct NeighbourGrid {
  glm::dvec3 lo{0.0};
  double cell = 1.0;
  glm::ivec3 dims{1};
  std::vector<uint32_t> offsets, items;

  glm::ivec3 cellOf(const glm::dvec3& p) const {
    return glm::clamp(glm::ivec3(glm::floor((p - lo) / cell)), glm::ivec3(0), dims - 1);
  }
  size_t index(const glm::ivec3& c) const { return (size_t(c.z) * dims.y + c.y) * dims.x + c.x; }

  NeighbourGrid(const std::vector<glm::vec3>& ps, double hn) {
    glm::dvec3 hi(-1e300);
    lo = glm::dvec3(1e300);
    for (const glm::vec3& p : ps) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
    if (ps.empty()) lo = hi = glm::dvec3(0.0);
    glm::dvec3 ext = hi - lo;
    // Sparse sets or a tiny h_n: coarser cells (still correct, more candidates) keep the grid at
    // about two cells per particle.
    const double max_cells = 2.0 * double(ps.size()) + 1024.0;
    cell = 0.5 * hn;
    for (;;) {
      glm::dvec3 n = glm::floor(ext / cell) + 1.0;
      if (n.x * n.y * n.z <= max_cells) {
        dims = glm::ivec3(n);
        break;
      }
      cell *= 1.5;
    }
    offsets.assign(size_t(dims.x) * dims.y * dims.z + 1, 0);
    std::vector<uint32_t> cell_of(ps.size());
    for (size_t i = 0; i < ps.size(); ++i) {
      cell_of[i] = uint32_t(index(cellOf(glm::dvec3(ps[i]))));
      ++offsets[cell_of[i] + 1];
    }
    for (size_t c = 0; c + 1 < offsets.size(); ++c) offsets[c + 1] += offsets[c];
    items.resize(ps.size());
    std::vector<uint32_t> cursor(offsets.begin(), offsets.end() - 1);
    for (size_t i = 0; i < ps.size(); ++i) items[cursor[cell_of[i]]++] = uint32_t(i);
  }
};

ParticleKernel roundKernel(double R, double R0, double h) {
  ParticleKernel k;
  k.a = glm::mat3(float(1.0 / R));
  double ratio = R0 / R;
  k.c = float(ratio * ratio * ratio);
  k.reach = float(R * h * (1.0 + 1e-6));
  k.axes = glm::mat3(float(R * h));
  return k;
}

}  // namespace

void validateAnisotropic(const AnisotropicParams& p) {
  if (!(p.rho_surface > p.rho_splash)) {
    char msg[256];
    std::snprintf(msg, sizeof msg,
                  "scene key 'particles.anisotropic.rho_surface': must be above "
                  "particles.anisotropic.rho_splash (%g), got %g",
                  p.rho_splash, p.rho_surface);
    throw InputError(msg);
  }
}

double anisotropicReachBound(const AnisotropicParams& p) {
  return (std::max(p.splash_scale, p.surface_scale) * std::sqrt(3.0) +
          p.position_smoothing * p.neighbourhood) *
         (1.0 + 1e-6);
}

std::vector<ParticleKernel> computeAnisotropicKernels(const std::vector<glm::vec3>& ps, double h,
                                                      const AnisotropicParams& p) {
  const double hn = p.neighbourhood * h, hn2 = hn * hn;
  const double R0 = p.splash_scale;
  std::vector<ParticleKernel> out(ps.size());
  if (ps.empty()) return out;
  NeighbourGrid grid(ps, hn);
  struct Neighbour {
    uint32_t j;
    double g;
  };
  // Every particle's kernel on its own (from the shared grid), so the particles are split over
  // the pixel threads (common/pixel_threads.h) in contiguous parts: the same kernels, bit for bit,
  // whatever the thread count.
  parallelFor(ps.size(), 1024, [&](size_t begin, size_t end) {
    std::vector<uint32_t> found;
    std::vector<Neighbour> near;
    for (size_t i = begin; i < end; ++i) {
      const glm::dvec3 ci(ps[i]);
      const glm::ivec3 c = grid.cellOf(ci);
      found.clear();
      const glm::ivec3 lo = glm::max(c - 2, glm::ivec3(0)), hi = glm::min(c + 2, grid.dims - 1);
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x) {
            glm::dvec3 box_lo = grid.lo + glm::dvec3(x, y, z) * grid.cell;
            glm::dvec3 gap =
                glm::max(glm::max(box_lo - ci, ci - (box_lo + grid.cell)), glm::dvec3(0.0));
            if (glm::dot(gap, gap) >= hn2) continue;
            size_t k = grid.index(glm::ivec3(x, y, z));
            for (uint32_t e = grid.offsets[k]; e < grid.offsets[k + 1]; ++e) {
              uint32_t j = grid.items[e];
              glm::dvec3 v = glm::dvec3(ps[j]) - ci;
              if (glm::dot(v, v) < hn2) found.push_back(j);
            }
          }
      // Ascending index: the same sums in the same order whatever subset holds the neighbourhood.
      // The sort is about a quarter of the time (perf, dam break); sorting the bare indices and
      // weighing them after measured within noise of sorting the weighted pairs (CPU 2.8-3.1 s
      // against 2.75-3.3 s for 5 runs on the dam break, one thread).
      std::sort(found.begin(), found.end());
      near.resize(found.size());
      for (size_t e = 0; e < found.size(); ++e) {
        glm::dvec3 v = glm::dvec3(ps[found[e]]) - ci;
        double u = 1.0 - glm::dot(v, v) / hn2;
        near[e] = {found[e], u * u * u};
      }
      double rho = 0.0;
      glm::dvec3 mu(0.0);
      for (const Neighbour& n : near) rho += n.g, mu += n.g * glm::dvec3(ps[n.j]);
      mu /= rho;  // rho >= 1: the particle itself is in the list with g = 1
      const double s = smoothstep(rho, p.rho_splash, p.rho_surface);
      const double R = (1.0 - s) * p.splash_scale + s * p.surface_scale;
      ParticleKernel k;
      if (s <= 0.0) {
        k = roundKernel(R, R0, h);  // splash: exactly the round metaball of radius R_splash h
      } else {
        Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
        for (const Neighbour& n : near) {
          glm::dvec3 v = glm::dvec3(ps[n.j]) - mu;
          double len2 = glm::dot(v, v);
          // Each term is a unit direction, whatever its length: a neighbour (or the particle
          // itself) almost on the mean would add a full-weight direction that rounding picks (in
          // a plane of particles the particle's own offset from the mean, 1e-8 h, tilted the disc
          // by 20 %). So directions fade in over the first kDirectionFade h_n from the mean:
          // weight g min(1, |c - mu|^2 / (kDirectionFade h_n)^2); none on the mean itself.
          const double fade = std::min(1.0, len2 / (kDirectionFade * kDirectionFade * hn2));
          if (!(fade > 0.0)) continue;
          Eigen::Vector3d e(v.x, v.y, v.z);
          S += (n.g * fade / len2) * (e * e.transpose());
        }
        const double trace = S.trace();
        if (!(trace > 0.0)) {
          k = roundKernel(R, R0, h);  // no usable direction: a sphere
        } else {
          Eigen::Matrix3d sigma = (1.0 - s) * Eigen::Matrix3d::Identity() + (s * 3.0 / trace) * S;
          // The iterative solver: Eigen's closed form (computeDirect) returned wrong eigenvectors
          // for the double eigenvalue of a plane of particles (axes off by 5 %).
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(sigma);
          Eigen::Vector3d l = eig.eigenvalues();  // ascending
          const double ratio2 = p.max_axis_ratio * p.max_axis_ratio;
          const double l_max =
              std::max(l(2), 1.0);  // trace 3: the largest is >= 1 (rounding aside)
          for (int a = 0; a < 3; ++a) l(a) = std::clamp(l(a), l_max / ratio2, l_max);
          const Eigen::Matrix3d& Q = eig.eigenvectors();
          Eigen::Vector3d inv_axis = (l.cwiseSqrt() * R).cwiseInverse();
          Eigen::Matrix3d A = Q * inv_axis.asDiagonal() * Q.transpose();
          for (int r = 0; r < 3; ++r)
            for (int col = 0; col < 3; ++col) k.a[col][r] = float(0.5 * (A(r, col) + A(col, r)));
          double ratio = R0 / R;
          k.c = float(ratio * ratio * ratio / std::sqrt(l(0) * l(1) * l(2)));
          k.reach = float(R * std::sqrt(l.maxCoeff()) * h * (1.0 + 1e-6));
          for (int a = 0; a < 3; ++a)
            for (int r = 0; r < 3; ++r) k.axes[a][r] = float(Q(r, a) * R * std::sqrt(l(a)) * h);
        }
      }
      // Computed in double from the same sums on every rank; lambda = 0 keeps c_i bit for bit.
      k.centre = p.position_smoothing == 0.0
                     ? ps[i]
                     : glm::vec3((1.0 - p.position_smoothing) * ci + p.position_smoothing * mu);
      k.s = float(s);
      k.rho = float(rho);
      out[i] = k;
    }
  });
  return out;
}

double maxReach(const std::vector<ParticleKernel>& kernels) {
  double r = 0.0;
  for (const ParticleKernel& k : kernels) r = std::max(r, double(k.reach));
  return r;
}

}  // namespace sortlast
