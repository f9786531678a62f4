// The isosurface reference's exact crossings (reference/isosurface_reference.h: a cubic per cell,
// split at its turning points, bisected) against a brute-force search of the same trilinear field
// (WholeVolume::at, the composite reference's sampler) along each ray: dense steps of 1e-3 voxel,
// every change of side bisected on at() itself. A wrong cubic, a missed cell face or a dropped
// monotone piece shows as a missing, extra or displaced crossing; gradients against central
// differences of at() inside the hit's cell.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "common/box.h"
#include "reference/isosurface_reference.h"

namespace sortlast {
namespace {

std::vector<double> bruteCrossings(const WholeVolume& vol, double iso, const glm::dvec3& o,
                                   const glm::dvec3& d, double ta, double tb, double h) {
  std::vector<double> out;
  auto f = [&](double t) { return vol.at(vol.grid.indexOfWorld(o + t * d)); };
  bool side = f(ta) >= iso;
  for (double a = ta; a < tb;) {
    const double b = std::min(a + h, tb);
    const bool s = f(b) >= iso;
    if (s != side) {
      double lo = a, hi = b;
      for (int i = 0; i < 100; ++i) {
        const double m = 0.5 * (lo + hi);
        ((f(m) >= iso) == side ? lo : hi) = m;
      }
      out.push_back(0.5 * (lo + hi));
      side = s;
    }
    a = b;
  }
  return out;
}

TEST(IsosurfaceReference, ExactCrossingsMatchABruteForceSearchOfTheTrilinearField) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  WholeVolume vol;
  vol.grid.dims = {7, 6, 8};
  vol.grid.spacing = {1.0, 0.7, 1.3};
  for (int i = 0; i < 7 * 6 * 8; ++i) vol.samples.push_back(float(u(rng)));
  const std::vector<Isovalue> iso = {{0.5, {1, 1, 1}, 0.5}, {0.3, {1, 1, 1}, 0.5}};
  const Box3 box = vol.grid.worldBox();
  int compared = 0, rays_differing = 0;
  double worst_dt = 0.0, worst_grad = 0.0;
  for (int r = 0; r < 200; ++r) {
    const glm::dvec3 o(20 * u(rng) - 10, 20 * u(rng) - 10, 30);
    const glm::dvec3 target(6 * u(rng) - 3, 4 * u(rng) - 2, 8 * u(rng) - 4);
    const glm::dvec3 d = glm::normalize(target - o);
    double t0, t1;
    if (!intersectRayBox(o, d, box, t0, t1)) continue;
    const std::vector<IsoHit> hits = isoCrossings(vol, iso, o, d, t0, t1);
    std::vector<std::vector<double>> mine(iso.size());
    for (const IsoHit& h : hits) mine[size_t(h.iso)].push_back(h.t);
    for (size_t j = 0; j < iso.size(); ++j) {
      const std::vector<double> want = bruteCrossings(vol, iso[j].value, o, d, t0, t1, 1e-3);
      if (want.size() != mine[j].size()) {  // only a pair closer than the brute step may differ
        ++rays_differing;
        continue;
      }
      for (size_t k = 0; k < want.size(); ++k) {
        worst_dt = std::max(worst_dt, std::abs(want[k] - mine[j][k]));
        ++compared;
      }
    }
    for (const IsoHit& h : hits) {
      // Central differences of at() over 1e-6 index units, inside the hit's cell unless the hit
      // lies within that of a face (then the one-sided limit differs: skipped).
      const glm::dvec3 idx = vol.grid.indexOfWorld(o + h.t * d);
      bool inside = true;
      for (int a = 0; a < 3; ++a) inside = inside && std::abs(idx[a] - std::round(idx[a])) > 1e-5;
      if (!inside) continue;
      glm::dvec3 g;
      for (int a = 0; a < 3; ++a) {
        glm::dvec3 e(0.0);
        e[a] = 1e-6;
        g[a] = (vol.at(idx + e) - vol.at(idx - e)) / (2e-6 * vol.grid.spacing[a]);
      }
      worst_grad = std::max(worst_grad, glm::length(g - h.gradient) / glm::length(g));
    }
  }
  std::printf("%d crossings compared, %d ray/value lists differing; worst |dt| %.3g, worst gradient %.3g (relative)\n",
              compared, rays_differing, worst_dt, worst_grad);
  // Measured: 831 crossings, no list differing, worst |dt| 1.4e-14, worst gradient 8.6e-10.
  EXPECT_GT(compared, 500);
  EXPECT_LE(rays_differing, 2);
  EXPECT_LE(worst_dt, 1e-10);
  EXPECT_LE(worst_grad, 1e-6);
}

TEST(IsosurfaceReference, StopsAtTheFirstOpaqueHit) {
  WholeVolume vol;
  vol.grid.dims = {2, 2, 2};
  vol.samples = {0, 1, 0, 1, 0, 1, 0, 1};  // value = x index: rises along x
  const glm::dvec3 o(-5, 0.1, 0.2), d(1, 0, 0);
  const Box3 box = vol.grid.worldBox();
  double t0, t1;
  ASSERT_TRUE(intersectRayBox(o, d, box, t0, t1));
  // 0.25 at x = -0.25, 0.75 at x = 0.25 (the box spans [-0.5, 0.5]).
  std::vector<IsoHit> hits = isoCrossings(vol, {{0.25, {1, 1, 1}, 1.0}, {0.75, {1, 1, 1}, 1.0}}, o, d, t0, t1);
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_NEAR(hits[0].t, 4.75, 1e-12);
  EXPECT_NEAR(hits[0].gradient.x, 1.0, 1e-12);
  hits = isoCrossings(vol, {{0.25, {1, 1, 1}, 0.5}, {0.75, {1, 1, 1}, 1.0}}, o, d, t0, t1);
  ASSERT_EQ(hits.size(), 2u);
  EXPECT_NEAR(hits[1].t, 5.25, 1e-12);
  EXPECT_EQ(hits[1].iso, 1);
}

}  // namespace
}  // namespace sortlast
