// The per-fragment subdivision renderer (render/surfaces/subdiv_renderer.h) on an OSMesa context: every
// covered pixel's limit point and normal against the exact double evaluation at the pixel's own
// (face, u, v), and that point on the pixel's ray away from silhouettes; images of coarse levels
// 1, 2, 3 against each other away from silhouettes; bricks composited by depth against the
// one-brick image.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "io/image.h"
#include "subdiv/subdiv_input.h"
#include "render/surfaces/subdiv_renderer.h"

namespace sortlast {
namespace {

constexpr int kSize = 160;

Camera camera(const PolyMesh& m) {
  Camera c;
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const auto& p : m.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  c.look_at = 0.5 * (lo + hi);
  c.position = c.look_at + glm::dvec3(0.9, 0.7, 1.6) * m.size() * 0.6;
  c.width = c.height = kSize;
  return c;
}

struct Fixture {
  PolyMesh input = proceduralMesh("pole5");
  SubdivSurface surface{input};
  std::unique_ptr<GlContext> ctx = createGlContext("osmesa");
  SubdivRenderer renderer{*ctx, kSize, kSize};
  Camera cam = camera(input);
  Box3 all{glm::dvec3(-1e3), glm::dvec3(1e3)};
  double near_plane = 0.05 * input.size(), far_plane = 10 * input.size();
  SubdivFrame render(int level, const Box3& clip, const std::string& mode = "headlight", bool params = false) {
    SubdivShading s;
    s.mode = mode;
    renderer.setSurface(surface, level, s);
    return renderer.render(cam, clip, near_plane, far_plane, params);
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

// Off the ray: the Newton steps move (u, v) until the limit point lies on the pixel's ray
// (Camera::rayDirection's, which the reference casts), continuing on the neighbouring face when a
// step leaves its face. Checked where the pixel's 5 x 5 neighbourhood is covered: at a silhouette
// the ray can miss the limit surface that the coarse mesh covers (there 1.8e-2 of the size at
// level 1). Measured 1.2e-6 of the size at most. It guards the shader's edge-crossing frames,
// which only pixels whose coarse fragment lies on another face than their limit point use: each
// of the eight branches (leaving edge c, entering edge d) given a = 1 - a along its edge moves
// 42-62 interior pixels off their ray at level 1, by up to 1.1e-2 to 1.0e-1 of the size (the
// image test below sees 2-11 pixels of it).
TEST(SubdivGl, EveryFragmentIsTheExactLimitPoint) {
  Fixture& f = fixture();
  for (int level = 1; level <= 3; ++level) {
    const SubdivFrame frame = f.render(level, f.all, "headlight", true);
    auto covered_at = [&](int x, int y) { return frame.parameters[(size_t(y) * kSize + x) * 4] >= 0; };
    constexpr double kOffRay = 1e-5;  // of the size
    int covered = 0, interior = 0, over = 0;
    double position = 0, normal = 0, off_ray = 0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
      const float* q = &frame.parameters[i * 4];
      if (q[0] < 0) continue;
      ++covered;
      const LimitPoint exact = f.surface.evaluate(int(q[0]), q[1], q[2]);
      const int x = int(i % kSize), y = int(i / kSize);
      bool inside = x >= 2 && y >= 2 && x < kSize - 2 && y < kSize - 2;
      for (int dy = -2; dy <= 2 && inside; ++dy)
        for (int dx = -2; dx <= 2 && inside; ++dx) inside = covered_at(x + dx, y + dy);
      if (inside) {
        ++interior;
        const glm::dvec3 ray = f.cam.rayDirection(x, y);
        const double off = glm::length(glm::cross(exact.position - f.cam.position, ray)) / f.input.size();
        off_ray = std::max(off_ray, off);
        over += off > kOffRay;
      }
      const float* s = &frame.surface[i * 4];
      position = std::max(position, std::abs(s[0] - glm::length(exact.position - f.cam.position)) / f.input.size());
      const glm::dvec3 n(s[1], s[2], s[3]);
      normal = std::max(normal, std::atan2(glm::length(glm::cross(n, exact.normal)), glm::dot(n, exact.normal)) * 180 /
                                    std::numbers::pi);
    }
    std::printf("  level %d: %d fragments, depth error %.2e of the size, normal %.2e deg; %d interior, off their ray "
                "by %.2e of the size (%d over %.0e)\n", level, covered, position, normal, interior, off_ray, over, kOffRay);
    EXPECT_GT(covered, kSize * kSize / 8);
    EXPECT_GT(interior, kSize * kSize / 10);
    EXPECT_LE(position, 1e-5);
    EXPECT_LE(normal, 0.05);
    EXPECT_LE(off_ray, kOffRay) << "level " << level;
  }
}

// Away from silhouettes (pixels whose 5 x 5 neighbourhood is covered at every level) the image
// does not depend on the coarse level: the Newton steps put every fragment's limit point on its
// pixel's ray. (Without them, as in the paper, the coarse fragment's interpolated (u, v) is up to
// the coarse mesh's deviation away: measured 16/255 headlight and 191/255 with hard stripes.)
TEST(SubdivGl, ImageDoesNotDependOnTheCoarseLevel) {
  Fixture& f = fixture();
  for (const std::string mode : {"headlight", "reflection_lines"}) {
    std::vector<SubdivFrame> frames;
    for (int level = 1; level <= 3; ++level) frames.push_back(f.render(level, f.all, mode));
    writeImage(::testing::TempDir() + "subdiv_" + mode + "_l1.png", frames[0].pixels, glm::dvec3(0.0));
    writeImage(::testing::TempDir() + "subdiv_" + mode + "_l3.png", frames[2].pixels, glm::dvec3(0.0));
    int compared = 0, worst = 0, over = 0;
    for (int y = 2; y < kSize - 2; ++y)
      for (int x = 2; x < kSize - 2; ++x) {
        bool inside = true;
        for (int dy = -2; dy <= 2 && inside; ++dy)
          for (int dx = -2; dx <= 2 && inside; ++dx)
            for (const auto& fr : frames) inside = inside && fr.pixels.at(x + dx, y + dy)[3] == 255;
        if (!inside) continue;
        ++compared;
        int d = 0;
        for (int c = 0; c < 3; ++c)
          d = std::max({d, std::abs(frames[0].pixels.at(x, y)[c] - frames[2].pixels.at(x, y)[c]),
                        std::abs(frames[1].pixels.at(x, y)[c] - frames[2].pixels.at(x, y)[c])});
        worst = std::max(worst, d);
        over += d > 1;
      }
    std::printf("  %s: %d interior pixels, worst difference %d/255, %d above 1/255\n", mode.c_str(), compared, worst, over);
    EXPECT_GT(compared, kSize * kSize / 10);
    EXPECT_LE(worst, 1) << mode;
  }
}

// Bricks: the box split in two along each axis in turn; per pixel the nearer limit point of the
// two brick images must be the one-brick image's, colour and depth. The torus seen at a grazing
// angle, so that one brick's surface hides the other's in many pixels. Every brick evaluates the
// same nearest coarse fragment per pixel, so each covered pixel is drawn by exactly one brick (the
// one holding its limit point); a brick does not draw its surface where another brick's hides it.
TEST(SubdivGl, BricksComposeToTheWholeImageExactly) {
  Fixture& f = fixture();
  const PolyMesh torus = proceduralMesh("torus");
  const SubdivSurface surface(torus);
  f.renderer.setSurface(surface, 2, SubdivShading());
  Camera cam = f.cam;
  cam.look_at = glm::dvec3(0.0);
  cam.position = glm::dvec3(0.3, 0.9, 0.35) * torus.size();
  auto render = [&](const Box3& clip) { return f.renderer.render(cam, clip, 0.05 * torus.size(), 10 * torus.size()); };
  const SubdivFrame whole = render(f.all);
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const auto& p : torus.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::dvec3 mid = 0.5 * (lo + hi);
  for (int axis = 0; axis < 3; ++axis) {
    Box3 a = f.all, b = f.all;
    a.hi[axis] = mid[axis];
    b.lo[axis] = mid[axis];
    const SubdivFrame fa = render(a), fb = render(b);
    int differ = 0, both = 0, onlyA = 0, onlyB = 0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
      const bool firstA = fa.surface[i * 4] <= fb.surface[i * 4];
      const SubdivFrame& near = firstA ? fa : fb;
      both += fa.pixels.px[i * 4 + 3] && fb.pixels.px[i * 4 + 3];
      onlyA += fa.pixels.px[i * 4 + 3] && !fb.pixels.px[i * 4 + 3];
      onlyB += !fa.pixels.px[i * 4 + 3] && fb.pixels.px[i * 4 + 3];
      for (int c = 0; c < 4; ++c) differ += near.pixels.px[i * 4 + c] != whole.pixels.px[i * 4 + c];
      differ += near.surface[i * 4] != whole.surface[i * 4];
    }
    std::printf("  split along axis %d: %d and %d pixels from one brick, %d from both, %d values differ\n", axis,
                onlyA, onlyB, both, differ);
    EXPECT_EQ(differ, 0) << axis;
    EXPECT_EQ(both, 0) << axis;
    EXPECT_GT(onlyA, 100) << axis;
    EXPECT_GT(onlyB, 100) << axis;
  }
}

}  // namespace
}  // namespace sortlast
