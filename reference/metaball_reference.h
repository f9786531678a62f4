#pragma once
// The metaball reference: a CPU ray caster in double precision of the same implicit surface the GL
// metaball renderer finds (Mishima, Tanaka and Sagawa, ../shared/PAPERS.md §2), what its accuracy is measured
// against.
//
// Model. Particles at P_j, influence radius h, threshold T:
//   F(x) = sum_j P(|x - P_j|),  P(r) = (1 - r/h)^2 for r <= h, else 0
//   I(x) = sqrt(F(x)) - T
// Along the ray x(t) = O + t D (D unit) the surface is the first t >= t_entry where I >= 0, t
// restricted to the ray's overlap with a clip box (a brick, or the whole domain) and to t >= 0. A
// ray that enters the box already inside (I(t_entry) >= 0) misses in that box: its surface lies in
// front, in another box. Normal N = -grad F / |grad F| (outward); grad F = 0 gives N = -D. In
// grad F the term of a particle at r = 0 is defined 0 (P is not differentiable there).
//
// Method. A uniform grid of cells of size h (anisotropic: the longest reach) finds the particles within h of the clipped ray: a
// 3D-DDA walks the cells the ray crosses, front to back, and every particle within h of a point
// lies in that point's cell or one of its 26 neighbours. Each such particle covers an exact
// interval [t_b - s, t_b + s] of the ray (t_b the closest approach, s = sqrt(h^2 - d^2)); outside
// their union F = 0 and there is no surface, so only the union is sampled, in steps of h/64 from
// t_entry (and at t_exit), summing F over the particles whose interval is current. The walk runs
// only as far ahead as the samples need, so a ray stops paying at its hit. The first sample with
// I >= 0 is bracketed with the last one below, bisected to |dt| < 1e-10 h and finished with one
// secant step.
//
// Limit. Fine stepping still misses a surface region thinner than the step along the ray (a
// sliver where I >= 0 between two samples h/64 apart, e.g. a ray grazing a sphere almost
// tangentially, or the neck between two particles just at the threshold). Such pixels are
// silhouette-like; compare with edge pixels ignored.
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <unordered_map>
#include <vector>

#include "io/anisotropic_kernels.h"
#include "common/box.h"
#include "common/camera.h"
#include "io/image.h"
#include "io/surface_image.h"

namespace sortlast {

struct MetaballModel {
  std::vector<glm::dvec3> positions;
  double h = 0.0;          // influence radius
  double threshold = 0.0;  // T
  // Anisotropic smoothing (io/anisotropic_kernels.h), one per particle; empty: round. Then
  //   P_j(x) = C_j (1 - |A_j (x - P_j)| / h)^2 where |A_j (x - P_j)| <= h,
  // in double from the same float kernels the GL ray caster uploads; the grid's cells and the
  // spans below use each particle's reach (longest semi-axis) instead of h.
  std::vector<ParticleKernel> kernels;
};

inline constexpr int kReferenceStepsPerH = 64;  // sample step h / 64

struct RayHit {
  double t = std::numeric_limits<double>::infinity();  // +infinity: no hit
  glm::dvec3 normal{0.0};
  bool hit() const { return std::isfinite(t); }
};

// The field with its neighbour grid, built once and shared (read-only) by every ray.
class MetaballField {
 public:
  // Throws InputError: h not positive and finite, T not positive and finite, a NaN or infinite
  // position, or a particle set too wide for cells of size h (over 2^30 cells along an axis).
  explicit MetaballField(MetaballModel model);

  double field(const glm::dvec3& x) const;         // F, summed over all particles near x
  glm::dvec3 gradient(const glm::dvec3& x) const;  // grad F
  double implicit(const glm::dvec3& x) const;      // I = sqrt(F) - T

  // The first surface point along O + t D (D unit) inside `clip`, or a miss.
  RayHit firstHit(const glm::dvec3& origin, const glm::dvec3& dir, const Box3& clip) const;

  const MetaballModel& model() const { return model_; }

 private:
  struct CellHash {
    size_t operator()(const glm::ivec3& c) const {
      return size_t(uint32_t(c.x)) * 73856093u ^ size_t(uint32_t(c.y)) * 19349663u ^
             size_t(uint32_t(c.z)) * 83492791u;
    }
  };
  friend class MetaballCellWalk;  // the ray's walk over the grid (metaball_reference.cpp)
  glm::ivec3 cellOf(const glm::dvec3& x) const;
  template <typename Visit>
  void forEachInCell(const glm::ivec3& c, Visit visit) const;

  double particleField(uint32_t j, const glm::dvec3& x) const;       // P_j(x)
  glm::dvec3 particleGradient(uint32_t j, const glm::dvec3& x) const;  // grad P_j(x)
  double particleReach(uint32_t j) const;

  MetaballModel model_;
  double cell_ = 1.0;            // grid cell edge: h, or the longest reach with kernels
  Box3 reach_;                   // the particles' bounds grown by h: F = 0 outside
  glm::dvec3 origin_{0.0};       // grid corner: the particles' lower bound
  glm::ivec3 cell_count_{0};     // cells spanning the particles' bounds
  std::vector<uint32_t> order_;  // particle indices grouped by cell
  std::unordered_map<glm::ivec3, std::pair<uint32_t, uint32_t>, CellHash> cells_;  // into order_
};

// Per pixel hit t (distance along the unit ray) and outward normal, rays clipped to `clip`.
// `threads` <= 0: all cores.
SurfaceImage referenceSurface(const MetaballModel& model, const Camera& cam, const Box3& clip,
                              int threads);

// Shades every hit pixel with transfer/metaball_shading.h (premultiplied, opaque); misses (0,0,0,0).
// Throws InputError if the surface image is not the camera's size.
ImageF shadeSurfaceFloat(const SurfaceImage& surface, const Camera& cam, const glm::dvec3& colour);
ImageRGBA8 shadeSurface(const SurfaceImage& surface, const Camera& cam, const glm::dvec3& colour);

}  // namespace sortlast
