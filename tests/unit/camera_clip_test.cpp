// The camera's two projections (common/camera.h), the visibility order with the eye inside the
// bricks and at infinity (common/visibility.h orderEye), the clip region's span and culling
// (common/clip.h), and the scene keys' bad input (camera.projection, camera.parallel_scale,
// clip.planes, clip.box).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "common/camera.h"
#include "common/clip.h"
#include "common/decomposition.h"
#include "common/visibility.h"
#include "scene/scene.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

Camera orthoCamera() {
  Camera c;
  c.position = {1.5, -0.7, 4.0};
  c.look_at = {0.2, 0.1, -0.3};
  c.up = {0.1, 1.0, 0.2};
  c.width = 64;
  c.height = 48;
  c.projection = Projection::kOrthographic;
  c.parallel_scale = 0.8;
  return c;
}

// Orthographic rays are parallel, start on the eye plane, and project() maps every point of a
// pixel's ray back to that pixel's centre; the view is 2 parallel_scale high and 2 parallel_scale
// x aspect wide.
TEST(Camera, OrthographicRaysRoundTripThroughProject) {
  const Camera c = orthoCamera();
  const glm::dvec3 f = c.forward();
  for (int y = 0; y < c.height; y += 7)
    for (int x = 0; x < c.width; x += 5) {
      const CameraRay r = c.pixelRay(x, y);
      EXPECT_NEAR(glm::length(r.direction - f), 0.0, 1e-15);
      EXPECT_NEAR(glm::dot(r.origin - c.position, f), 0.0, 1e-12);  // on the eye plane
      for (double t : {0.5, 3.0, 40.0}) {
        auto p = c.project(r.origin + t * r.direction);
        ASSERT_TRUE(p);
        EXPECT_NEAR(p->x, x + 0.5, 1e-9);
        EXPECT_NEAR(p->y, y + 0.5, 1e-9);
      }
    }
  // Corner pixels' origins span the view: 2 s high, 2 s aspect wide (less a pixel).
  const glm::dvec3 a = c.pixelRay(0, 0).origin, b = c.pixelRay(c.width - 1, c.height - 1).origin;
  EXPECT_NEAR(glm::dot(a - b, c.trueUp()), 2 * 0.8 * (1.0 - 1.0 / c.height), 1e-12);
  EXPECT_NEAR(glm::dot(b - a, c.right()), 2 * 0.8 * 64.0 / 48.0 * (1.0 - 1.0 / c.width), 1e-12);
  // Behind the eye plane: not seen.
  EXPECT_FALSE(c.project(c.position - 0.1 * f));
}

// viewProjection (what GL rasterises with) puts a point where project() does, in both projections
// (window row 0 = image row 0: y flipped).
TEST(Camera, ViewProjectionAgreesWithProject) {
  for (Projection pr : {Projection::kPerspective, Projection::kOrthographic}) {
    Camera c = orthoCamera();
    c.projection = pr;
    const glm::dmat4 vp(c.viewProjection(0.5, 20.0));
    for (glm::dvec3 q : {glm::dvec3(0.2, 0.1, -0.3), glm::dvec3(0.6, -0.2, 0.4), glm::dvec3(-0.4, 0.5, 1.0)}) {
      const glm::dvec4 clip = vp * glm::dvec4(q, 1.0);
      const glm::dvec2 ndc(clip.x / clip.w, clip.y / clip.w);
      auto p = c.project(q);
      ASSERT_TRUE(p);
      EXPECT_NEAR((ndc.x + 1.0) * 0.5 * c.width, p->x, 1e-4);
      EXPECT_NEAR((ndc.y + 1.0) * 0.5 * c.height, p->y, 1e-4);  // flipped: +y is down
    }
  }
}

// A box holding the eye covers the whole screen; one wholly behind the eye plane covers nothing;
// an orthographic box's rectangle holds every pixel whose ray meets it.
TEST(Camera, ScreenRectOfBoxesAroundAndBehindTheEye) {
  Camera c;
  c.position = {0.1, 0.2, 0.3};
  c.look_at = {0.1, 0.2, -5.0};
  c.width = 40;
  c.height = 30;
  EXPECT_EQ(screenRectOf(c, Box3{{-1, -1, -1}, {1, 1, 1}}), (Rect{0, 0, 40, 30}));
  EXPECT_TRUE(screenRectOf(c, Box3{{-1, -1, 0.3}, {1, 1, 2}}).empty());  // at and behind the plane
  EXPECT_FALSE(screenRectOf(c, Box3{{-1, -1, -2}, {1, 1, -1}}).empty());
  Camera o = orthoCamera();
  const Box3 box{{-0.3, -0.2, -0.1}, {0.4, 0.25, 0.3}};
  const Rect r = screenRectOf(o, box);
  ASSERT_FALSE(r.empty());
  int hits = 0;
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) {
      const CameraRay ray = o.pixelRay(x, y);
      double t0, t1;
      if (!intersectRayBox(ray.origin, ray.direction, box, t0, t1) || t1 <= std::max(t0, 0.0)) continue;
      ++hits;
      EXPECT_TRUE(x >= r.x && x < r.x + r.w && y >= r.y && y < r.y + r.h) << x << ", " << y;
    }
  EXPECT_GT(hits, 20);
  // Wholly behind the orthographic eye plane.
  Box3 behind{o.position + 2.0 * (o.position - o.look_at) - 0.1, o.position + 2.0 * (o.position - o.look_at) + 0.1};
  EXPECT_TRUE(screenRectOf(o, behind).empty());
}

using Planes = std::array<std::vector<double>, 3>;

// Parallel rays: along every direction, of two bricks sharing a face the one a ray meets later
// comes earlier in the order (bricks and rank regions), with the eye at infinity (orderEye).
TEST(Visibility, OrthographicOrderFollowsTheViewDirection) {
  const Planes planes = {std::vector<double>{-1.0, -0.2, 0.5, 1.0}, {0.0, 0.3, 0.9, 2.0}, {-2.0, -1.0, 0.0, 0.5}};
  const Box3 all{{-1.0, 0.0, -2.0}, {1.0, 2.0, 0.5}};
  std::mt19937 rng(42);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    Camera c = orthoCamera();
    glm::dvec3 f(n(rng), n(rng), n(rng));
    if (trial % 10 == 0) f[trial % 3] = 0.0;  // parallel to one axis's planes
    c.look_at = c.position + f;
    c.up = glm::cross(f, glm::dvec3(0.3, 0.7, 0.1));
    const glm::dvec3 eye = orderEye(c, all);
    const std::vector<int> order = backToFrontOrder(planes, eye);
    std::vector<int> pos(order.size());
    for (size_t i = 0; i < order.size(); ++i) pos[size_t(order[i])] = int(i);
    const glm::dvec3 d = c.forward();
    for (int z = 0; z < 3; ++z)
      for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x)
          for (int a = 0; a < 3; ++a) {
            glm::ivec3 lo(x, y, z), hi = lo;
            if (++hi[a] > 2 || d[a] == 0.0) continue;
            const int il = lo.x + 3 * (lo.y + 3 * lo.z), ih = hi.x + 3 * (hi.y + 3 * hi.z);
            // d[a] > 0: rays meet lo first, so hi (behind) is drawn first.
            if (d[a] > 0) EXPECT_LT(pos[size_t(ih)], pos[size_t(il)]) << trial;
            else EXPECT_LT(pos[size_t(il)], pos[size_t(ih)]) << trial;
          }
    // Ranks: a rank whose region a ray enters later comes first.
    const Assignment as = assignBricks(3, 4);
    const std::vector<int> ranks = backToFrontRanks(as, planes, eye);
    ASSERT_EQ(ranks.size(), 4u);
    std::vector<int> rpos(4);
    for (int i = 0; i < 4; ++i) rpos[size_t(ranks[size_t(i)])] = i;
    for (int r = 0; r < 4; ++r)
      for (int s = 0; s < 4; ++s) {
        if (r == s) continue;
        const Box3 br = cellRangeBox(planes, as.region[size_t(r)]), bs = cellRangeBox(planes, as.region[size_t(s)]);
        // kd regions are separated along some axis; the region further along d is behind where
        // every separating axis says so (where they disagree, or d is parallel to one, no ray
        // meets both and either order is right).
        int behind = 0;  // +1: s behind r, -1: r behind s, 2: no constraint
        for (int a = 0; a < 3; ++a) {
          int says = 0;
          if (br.hi[a] <= bs.lo[a]) says = d[a] > 0 ? 1 : d[a] < 0 ? -1 : 2;
          else if (bs.hi[a] <= br.lo[a]) says = d[a] > 0 ? -1 : d[a] < 0 ? 1 : 2;
          if (says == 0) continue;
          behind = behind == 0 || behind == says ? says : 2;
        }
        if (behind == 1) EXPECT_LT(rpos[size_t(s)], rpos[size_t(r)]) << trial;
        if (behind == -1) EXPECT_LT(rpos[size_t(r)], rpos[size_t(s)]) << trial;
      }
  }
}

// The eye inside a brick: that brick is drawn last, and the rank that owns it is the last of the
// ranks.
TEST(Visibility, EyeInsideItsBrickAndRankComeLast) {
  const Planes planes = {std::vector<double>{-1.0, -0.2, 0.5, 1.0}, {0.0, 0.3, 0.9, 2.0}, {-2.0, -1.0, 0.0, 0.5}};
  for (int P = 1; P <= 4; ++P) {
    const Assignment as = assignBricks(3, P);
    for (int x = 0; x < 3; ++x)
      for (int y = 0; y < 3; ++y)
        for (int z = 0; z < 3; ++z) {
          const glm::dvec3 eye(0.5 * (planes[0][size_t(x)] + planes[0][size_t(x) + 1]),
                               0.5 * (planes[1][size_t(y)] + planes[1][size_t(y) + 1]),
                               0.5 * (planes[2][size_t(z)] + planes[2][size_t(z) + 1]));
          const int cell = x + 3 * (y + 3 * z);
          EXPECT_EQ(backToFrontOrder(planes, eye).back(), cell);
          const std::vector<int> ranks = backToFrontRanks(as, planes, eye);
          EXPECT_EQ(ranks.back(), as.owner[size_t(cell)]) << "P " << P << " cell " << cell;
        }
  }
}

// clipSpan: a plane keeps n . x <= w (the span's far end or near end moves, by the ray's
// direction), a ray parallel to a plane is kept whole or not at all, the box clips as its faces.
TEST(Clip, SpanAndCulling) {
  ClipRegion c;
  c.planes.push_back({{2.0, 0.0, 0.0}, 1.0});  // x <= 0.5
  double t0 = 0.0, t1 = 10.0;
  clipSpan(c, {-1, 0, 0}, {1, 0, 0}, t0, t1);
  EXPECT_DOUBLE_EQ(t0, 0.0);
  EXPECT_DOUBLE_EQ(t1, 1.5);
  t0 = 0.0, t1 = 10.0;
  clipSpan(c, {2, 0, 0}, {-1, 0, 0}, t0, t1);
  EXPECT_DOUBLE_EQ(t0, 1.5);
  EXPECT_DOUBLE_EQ(t1, 10.0);
  t0 = 0.0, t1 = 10.0;
  clipSpan(c, {0.6, 0, 0}, {0, 1, 0}, t0, t1);  // parallel, beyond
  EXPECT_GE(t0, t1);
  t0 = 0.0, t1 = 10.0;
  clipSpan(c, {0.4, 0, 0}, {0, 1, 0}, t0, t1);  // parallel, kept
  EXPECT_DOUBLE_EQ(t1, 10.0);
  c.has_box = true;
  c.box = {{-1, -1, -1}, {1, 0.25, 1}};
  t0 = 0.0, t1 = 10.0;
  clipSpan(c, {0, -3, 0}, {0, 1, 0}, t0, t1);
  EXPECT_DOUBLE_EQ(t0, 2.0);
  EXPECT_DOUBLE_EQ(t1, 3.25);
  EXPECT_EQ(c.halfSpaces().size(), 7u);
  EXPECT_TRUE(c.culls(Box3{{0.6, -1, -1}, {2, 0, 0}}));    // beyond the plane
  EXPECT_TRUE(c.culls(Box3{{-1, 0.3, -1}, {0, 1, 0}}));    // outside the box
  EXPECT_FALSE(c.culls(Box3{{0.4, -1, -1}, {2, 0, 0}}));   // straddles the plane
  EXPECT_FALSE(ClipRegion{}.culls(Box3{{0, 0, 0}, {1, 1, 1}}));
}

TEST(Clip, SceneKeysAndBadInput) {
  Scene s = loadScene("", {"clip.planes=[{normal: [0, 0, 1], offset: 0.1}, {normal: [1, 1, 0], offset: 0}]",
                           "clip.box=[[-0.4, -0.4, -0.4], [0.4, 0.4, 0.4]]"});
  ASSERT_EQ(s.clip.planes.size(), 2u);
  EXPECT_EQ(s.clip.planes[1].normal, glm::dvec3(1, 1, 0));
  EXPECT_TRUE(s.clip.has_box);
  EXPECT_FALSE(loadScene("", {}).clip.active());
  auto has = [](const std::string& m, const char* w) { return m.find(w) != std::string::npos; };
  std::string m = inputErrorOf([] { loadScene("", {"clip.planes=[{normal: [0, 0, 0], offset: 1}]"}); });
  EXPECT_TRUE(has(m, "clip.planes") && has(m, "zero")) << m;
  m = inputErrorOf([] { loadScene("", {"clip.planes=[{normal: [0, 0, 1]}]"}); });
  EXPECT_TRUE(has(m, "clip.planes") && has(m, "offset")) << m;
  m = inputErrorOf([] { loadScene("", {"clip.box=[[0, 0, 0], [1, 0, 1]]"}); });
  EXPECT_TRUE(has(m, "clip.box") && has(m, "empty")) << m;
  m = inputErrorOf([] { loadScene("", {"camera.parallel_scale=0"}); });
  EXPECT_TRUE(has(m, "camera.parallel_scale")) << m;
  m = inputErrorOf([] { loadScene("", {"camera.parallel_scale=-2"}); });
  EXPECT_TRUE(has(m, "camera.parallel_scale")) << m;
  m = inputErrorOf([] { loadScene("", {"camera.projection=fisheye"}); });
  EXPECT_TRUE(has(m, "camera.projection") && has(m, "orthographic")) << m;
  // Every renderer takes parallel rays: particles, surfaces and glow are accepted.
  EXPECT_NO_THROW(loadScene("", {"camera.projection=orthographic", "particles.procedural=layers"}));
  EXPECT_NO_THROW(loadScene("", {"camera.projection=orthographic", "surfaces=[{procedural: pole5}]"}));
  EXPECT_NO_THROW(loadScene("", {"camera.projection=orthographic", "glow.emitters=[{center: [0, 0, 0]}]",
                                 "glow.box=[[-1, -1, -1], [1, 1, 1]]"}));
  // A clip cuts volumes only: glow emitters are drawn with it (tests/mpi/glow.sh against the reference).
  EXPECT_NO_THROW(loadScene("", {"clip.planes=[{normal: [1, 0, 0], offset: 0}]", "glow.emitters=[{center: [0, 0, 0]}]"}));
  // parallel_scale auto: the perspective view's half height at the look-at point.
  Scene o = loadScene("", {"camera.projection=orthographic", "camera.position=[0, 0, 4]", "camera.look_at=[0, 0, 0]", "camera.fov=90"});
  const Camera c = o.frameCameras(Box3{{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}})[0];
  EXPECT_TRUE(c.orthographic());
  EXPECT_NEAR(c.parallel_scale, 4.0, 1e-12);
}

}  // namespace
}  // namespace sortlast
