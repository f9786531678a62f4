// View-aligned slice polygons through a brick (render/volume/slice_geometry.h): vertices on their planes
// and inside the box, far-to-near order, exact cross-section areas, and bit-identical vertices on
// a face shared by two bricks.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "common/box.h"
#include "render/volume/slice_geometry.h"

namespace sortlast {
namespace {

struct Tri {
  glm::dvec3 p[3];
};

std::vector<Tri> toTris(const std::vector<float>& v) {
  EXPECT_EQ(v.size() % 9, 0u);
  std::vector<Tri> t(v.size() / 9);
  for (size_t i = 0; i < t.size(); ++i)
    for (int k = 0; k < 3; ++k) t[i].p[k] = {v[9 * i + 3 * k], v[9 * i + 3 * k + 1], v[9 * i + 3 * k + 2]};
  return t;
}

double triArea(const Tri& t) { return 0.5 * glm::length(glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0])); }

// Area of the plane {x : f . (x - eye) = t} inside `box`, by clipping a large square of the plane
// against the box's six half-spaces (independent of the code under test).
double crossSectionArea(const Box3& box, const glm::dvec3& eye, const glm::dvec3& f, double t) {
  glm::dvec3 u = glm::normalize(glm::cross(f, std::abs(f.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1)));
  glm::dvec3 v = glm::cross(f, u);
  glm::dvec3 q = eye + t * f;
  double L = 100.0;
  std::vector<glm::dvec3> poly = {q - L * u - L * v, q + L * u - L * v, q + L * u + L * v, q - L * u + L * v};
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      // Keep points with s(p) >= 0.
      auto s = [&](const glm::dvec3& p) { return side == 0 ? p[a] - box.lo[a] : box.hi[a] - p[a]; };
      std::vector<glm::dvec3> out;
      for (size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec3 &A = poly[i], &B = poly[(i + 1) % poly.size()];
        double sa = s(A), sb = s(B);
        if (sa >= 0) out.push_back(A);
        if ((sa >= 0) != (sb >= 0)) out.push_back(A + (B - A) * (sa / (sa - sb)));
      }
      poly = out;
      if (poly.empty()) return 0.0;
    }
  glm::dvec3 n(0.0);
  for (size_t i = 0; i < poly.size(); ++i) n += glm::cross(poly[i], poly[(i + 1) % poly.size()]);
  return 0.5 * std::abs(glm::dot(n, f));
}

glm::dvec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
}

TEST(SliceGeometry, VerticesOnPlanesInsideBoxFarToNearWithExactAreas) {
  const Box3 box{{0, 0, 0}, {1, 1, 1}};
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int checked_planes = 0;
  for (int trial = 0; trial < 200; ++trial) {
    glm::dvec3 eye = box.centre() + randomUnit(rng) * (1.0 + 5.0 * uni(rng));
    if (box.contains(eye)) continue;
    glm::dvec3 target = box.centre() + 0.3 * glm::dvec3(uni(rng) - 0.5, uni(rng) - 0.5, uni(rng) - 0.5);
    glm::dvec3 f = glm::normalize(target - eye);
    double spacing = 0.02 + 0.2 * uni(rng);
    double min_t = trial % 3 == 0 ? 0.0 : glm::dot(f, box.centre() - eye) + (uni(rng) - 0.5);
    SCOPED_TRACE("trial " + std::to_string(trial));
    auto tris = toTris(sliceTriangles(box, eye, f, spacing, min_t));
    std::map<long long, double> area;  // plane index -> total triangle area
    long long prev_k = LLONG_MAX;
    for (size_t i = 0; i < tris.size(); ++i) {
      const Tri& tr = tris[i];
      long long k = std::llround(glm::dot(f, tr.p[0] - eye) / spacing);
      for (int j = 0; j < 3; ++j) {
        double t = glm::dot(f, tr.p[j] - eye);
        ASSERT_NEAR(t, double(k) * spacing, 1e-4) << "triangle " << i << " vertex " << j;
        for (int a = 0; a < 3; ++a) {
          ASSERT_GE(tr.p[j][a], box.lo[a] - 1e-5) << "triangle " << i << " vertex " << j;
          ASSERT_LE(tr.p[j][a], box.hi[a] + 1e-5) << "triangle " << i << " vertex " << j;
        }
      }
      ASSERT_GT(double(k) * spacing, min_t) << "triangle " << i;
      ASSERT_LE(k, prev_k) << "triangle " << i << ": planes must go far to near";
      prev_k = k;
      area[k] += triArea(tr);
    }
    // Every plane in range has the exact cross-section area (planes the code skipped have none).
    double tmin = 1e300, tmax = -1e300;
    for (int c = 0; c < 8; ++c) {
      double t = glm::dot(f, box.corner(c) - eye);
      tmin = std::min(tmin, t), tmax = std::max(tmax, t);
    }
    for (long long k = (long long)std::floor(std::max(tmin, min_t) / spacing) - 1;
         k <= (long long)std::ceil(tmax / spacing) + 1; ++k) {
      double t = double(k) * spacing;
      double want = t > min_t ? crossSectionArea(box, eye, f, t) : 0.0;
      double got = area.count(k) ? area[k] : 0.0;
      ASSERT_NEAR(got, want, 2e-5) << "plane " << k << " at t = " << t;
      if (want > 1e-3) ++checked_planes;
    }
  }
  EXPECT_GT(checked_planes, 1000);
}

TEST(SliceGeometry, EyeOnZAxisGivesFullSquares) {
  const Box3 box{{0, 0, 0}, {1, 1, 1}};
  const glm::dvec3 eye(0.5, 0.5, 5.0), f(0.0, 0.0, -1.0);
  // Spacing 1/8 (exact in binary): planes at t = 4 (z = 1) ... t = 5 (z = 0). A corner on a plane
  // counts as behind it, so the near face z = 1 is a slice and the far face z = 0 is not.
  auto tris = toTris(sliceTriangles(box, eye, f, 0.125, 0.0));
  std::map<double, double, std::greater<double>> area_at_z;
  std::vector<double> zs;
  for (const Tri& t : tris) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_EQ(t.p[j].z, t.p[0].z);
      EXPECT_TRUE(t.p[j].x == 0.0 || t.p[j].x == 1.0) << t.p[j].x;
      EXPECT_TRUE(t.p[j].y == 0.0 || t.p[j].y == 1.0) << t.p[j].y;
    }
    if (zs.empty() || zs.back() != t.p[0].z) zs.push_back(t.p[0].z);
    area_at_z[t.p[0].z] += triArea(t);
  }
  // Far to near: z increases (the eye is at +z).
  ASSERT_EQ(zs, (std::vector<double>{0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0}));
  for (auto& [z, a] : area_at_z) EXPECT_NEAR(a, 1.0, 1e-6) << "z = " << z;
}

TEST(SliceGeometry, MinTDropsNearPlanes) {
  const Box3 box{{0, 0, 0}, {1, 1, 1}};
  const glm::dvec3 eye(0.5, 0.5, 5.0), f(0.0, 0.0, -1.0);
  // min_t = 4.3: only planes at t = 4.375 ... 4.875 (z = 0.625 ... 0.125) remain.
  auto tris = toTris(sliceTriangles(box, eye, f, 0.125, 4.3));
  std::set<double> zs;
  for (const Tri& t : tris) zs.insert(t.p[0].z);
  EXPECT_EQ(zs, (std::set<double>{0.125, 0.25, 0.375, 0.5, 0.625}));
  // Everything in front of min_t: nothing.
  EXPECT_TRUE(sliceTriangles(box, eye, f, 0.125, 6.0).empty());
  // Box behind the eye: nothing.
  EXPECT_TRUE(sliceTriangles(box, eye, -f, 0.125, 0.0).empty());
}

TEST(SliceGeometry, MinTIsAStrictBound) {
  // The header: "every slice polygon with plane distance > min_t". With min_t exactly on a plane
  // (t = 4.5, z = 0.5), that plane must not be emitted.
  const Box3 box{{0, 0, 0}, {1, 1, 1}};
  const glm::dvec3 eye(0.5, 0.5, 5.0), f(0.0, 0.0, -1.0);
  auto tris = toTris(sliceTriangles(box, eye, f, 0.125, 4.5));
  std::set<double> zs;
  for (const Tri& t : tris) zs.insert(t.p[0].z);
  EXPECT_EQ(zs, (std::set<double>{0.125, 0.25, 0.375}));
}

TEST(SliceGeometry, FaceBetweenStackedBricksIsSlicedOnce) {
  // Bricks z in [0, 1] and [1, 2], eye on +z: the plane through z = 1 belongs to exactly one.
  const Box3 lower{{0, 0, 0}, {1, 1, 1}}, upper{{0, 0, 1}, {1, 1, 2}};
  const glm::dvec3 eye(0.3, 0.6, 7.0), f(0.0, 0.0, -1.0);
  std::multiset<double> zs;
  for (const Box3& b : {lower, upper}) {
    std::set<double> mine;
    for (const Tri& t : toTris(sliceTriangles(b, eye, f, 0.25, 0.0))) mine.insert(t.p[0].z);
    zs.insert(mine.begin(), mine.end());
  }
  EXPECT_EQ(zs, (std::multiset<double>{0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0}));
}

TEST(SliceGeometry, SharedFaceVerticesAreBitIdentical) {
  const Box3 a{{0, 0, 0}, {1, 1, 1}}, b{{1, 0, 0}, {2, 1, 1}};
  const Box3 both{{0, 0, 0}, {2, 1, 1}};
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  using Key = std::tuple<uint32_t, uint32_t, uint32_t>;
  auto key = [](float x, float y, float z) {
    uint32_t k[3];
    std::memcpy(&k[0], &x, 4), std::memcpy(&k[1], &y, 4), std::memcpy(&k[2], &z, 4);
    return Key{k[0], k[1], k[2]};
  };
  // Vertices of `v` that lie on the face x = 1.
  auto onFace = [&](const std::vector<float>& v) {
    std::set<Key> s;
    for (size_t i = 0; i + 2 < v.size(); i += 3)
      if (v[i] == 1.0f) s.insert(key(v[i], v[i + 1], v[i + 2]));
    return s;
  };
  size_t shared = 0;
  for (int trial = 0; trial < 300; ++trial) {
    glm::dvec3 eye = both.centre() + randomUnit(rng) * (1.5 + 6.0 * uni(rng));
    if (both.contains(eye)) continue;
    glm::dvec3 target = both.centre() + glm::dvec3(uni(rng) - 0.5, 0.4 * (uni(rng) - 0.5), 0.4 * (uni(rng) - 0.5));
    glm::dvec3 f = glm::normalize(target - eye);
    double spacing = 0.01 + 0.1 * uni(rng);
    auto fa = onFace(sliceTriangles(a, eye, f, spacing, 0.0));
    auto fb = onFace(sliceTriangles(b, eye, f, spacing, 0.0));
    EXPECT_EQ(fa, fb) << "trial " << trial << ": " << fa.size() << " vs " << fb.size() << " face vertices";
    shared += fa.size();
  }
  EXPECT_GT(shared, 1000u);
}

}  // namespace
}  // namespace sortlast
