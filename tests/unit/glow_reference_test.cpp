// Glow in scenes: the glow.* keys' validation (scene/glow_scene.h), and the reference path
// (reference/glow_reference.h, reference/reference.h): per pixel against quadrature, split over bricks,
// and dimmed by a volume against the exact transmittance-weighted integral.
#include "reference/glow_reference.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "reference/glow_quadrature.h"
#include "scene/scene.h"
#include "reference/frame_reference.h"
#include "reference/reference.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

Scene parse(const std::string& yaml, std::vector<std::string> overrides = {}) {
  return parseScene({"glow_test.yaml", yaml}, overrides);
}

const char* kGlowOnly =
    "volume: {procedural: none}\n"
    "glow:\n"
    "  box: [[-2, -2, -2], [2, 2, 2]]\n"
    "  emitters:\n"
    "    - {center: [0, 0, 0], direction: [1, 0, 0], a: 1, b: 0.5, color: [1, 0.5, 0.25]}\n";

TEST(GlowScene, KeysParsedAndAnimated) {
  Scene s = parse(
      kGlowOnly, {"camera.orbit.frames=4",
                  "glow.emitters=[{center: [0, 0, 0], direction: [0, 0, 2], "
                  "a: 1, b: 2, velocity: [1, 0, 0], turn: [0, 2, 0], a_rate: 0.5, b_rate: -0.5}]"});
  ASSERT_EQ(s.glow.emitters.size(), 1u);
  std::vector<GlowEmitter> f3 = s.glow.emittersAt(3);
  EXPECT_DOUBLE_EQ(f3[0].centre.x, 3.0);
  EXPECT_DOUBLE_EQ(f3[0].a, 2.5);
  EXPECT_DOUBLE_EQ(f3[0].b, 0.5);
  EXPECT_NEAR(glm::length(f3[0].direction), 1.0, 1e-15);
  EXPECT_NEAR(f3[0].direction.y / f3[0].direction.z, 3.0, 1e-12);  // (0, 6, 2) normalised
  EXPECT_NEAR(glm::length(s.glow.emittersAt(0)[0].direction), 1.0, 1e-15);
}

TEST(GlowScene, BadKeysNameTheKey) {
  auto err = [](const std::string& yaml, std::vector<std::string> o = {}) {
    return inputErrorOf([&] { parse(yaml, o); });
  };
  auto with = [](const std::string& emitter) {
    return std::string(
               "volume: {procedural: none}\nglow: {box: [[-1, -1, -1], [1, 1, 1]], emitters: [") +
           emitter + "]}\n";
  };
  EXPECT_NE(err(with("{center: [0, 0, 0], a: -1}")).find("glow.emitters[0].a': must be >= 0"),
            std::string::npos);
  EXPECT_NE(err(with("{center: [0, 0, 0], b: -0.5}")).find("glow.emitters[0].b'"),
            std::string::npos);
  EXPECT_NE(err(with("{center: [0, 0, 0], direction: [0, 0, 0]}"))
                .find("glow.emitters[0].direction': must not be zero"),
            std::string::npos);
  EXPECT_NE(
      err(with("{center: [.nan, 0, 0]}")).find("glow.emitters[0].center': values must be finite"),
      std::string::npos);
  EXPECT_NE(err(with("{center: [0, 0, 0], a: .inf}")).find("glow.emitters[0].a': must be finite"),
            std::string::npos);
  EXPECT_NE(err(with("{center: [0, 0]}")).find("glow.emitters[0].center': expected a list of 3"),
            std::string::npos);
  EXPECT_NE(err(with("{direction: [1, 0, 0]}")).find("glow.emitters[0].center': required"),
            std::string::npos);
  EXPECT_NE(err(with("{center: [0, 0, 0], colour: [1, 0, 0]}"))
                .find("unknown scene key 'glow.emitters[0].colour'"),
            std::string::npos);
  EXPECT_NE(err(with("{center: [0, 0, 0], color: [2, 0, 0]}")).find("glow.emitters[0].color'"),
            std::string::npos);
  EXPECT_NE(err(with("{center: [0, 0, 0]}, 7")).find("glow.emitters[1]': expected a map"),
            std::string::npos);
  EXPECT_NE(err(with("{center: [0, 0, 0], a: 1, a_rate: -0.5}"), {"camera.orbit.frames=4"})
                .find("negative at frame 3"),
            std::string::npos);
  EXPECT_NE(err(with("{center: [0, 0, 0], direction: [1, 0, 0], turn: [-0.5, 0, 0]}"),
                {"camera.orbit.frames=4"})
                .find("direction becomes zero at frame 2"),
            std::string::npos);
  EXPECT_NE(err(kGlowOnly, {"glow.emitters=7"}).find("'glow.emitters': expected a list"),
            std::string::npos);
  EXPECT_NE(err(kGlowOnly, {"glow.core_radius=0"}).find("glow.core_radius"), std::string::npos);
  EXPECT_NE(err(kGlowOnly, {"glow.intensity=-1"}).find("glow.intensity"), std::string::npos);
  EXPECT_NE(err(kGlowOnly, {"glow.tone_map=reinhard"})
                .find("glow.tone_map': expected none or exponential"),
            std::string::npos);
  EXPECT_NE(err(kGlowOnly, {"glow.exposure=0"}).find("glow.exposure"), std::string::npos);
  EXPECT_NE(err(kGlowOnly, {"glow.box=[[0, 0, 0], [1, 0, 1]]"}).find("glow.box': needs lo < hi"),
            std::string::npos);
  EXPECT_NE(
      err(kGlowOnly, {"glow.box=auto"}).find("glow.box': a scene of glow emitters alone must set"),
      std::string::npos);
  EXPECT_NE(err("volume: {procedural: none}\n").find("glow.emitters is empty"), std::string::npos);
}

// An emitter with its beam crossing a 4^3 box, and the camera's rays through it.
GlowSpec spec() {
  GlowSpec g;
  GlowEmitterSpec e;
  e.at0.centre = {-0.7, 0.1, 0.2};
  e.at0.direction = glm::normalize(glm::dvec3(1, 0.3, -0.2));
  e.at0.a = 1.0;
  e.at0.b = 0.6;
  e.at0.colour = {1.0, 0.5, 0.25};
  g.emitters.push_back(e);
  e.at0.centre = {0.8, -0.4, 0.0};
  e.at0.direction = {0, 1, 0};
  e.at0.a = 0.3;
  e.at0.b = 1.2;
  e.at0.colour = {0.2, 0.6, 1.0};
  g.emitters.push_back(e);
  g.core_radius = 0.02;
  g.intensity = 0.7;
  return g;
}

Camera camera() {
  Camera c;
  c.position = {0.3, 1.1, 6.0};
  c.look_at = {0, 0, 0};
  c.width = 24;
  c.height = 18;
  return c;
}

TEST(GlowReference, PixelsMatchQuadrature) {
  const Box3 box{glm::dvec3(-2.0), glm::dvec3(2.0)};
  GlowRays rays(spec(), box, 0);
  Camera cam = camera();
  double worst = 0.0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      glm::dvec3 d = cam.rayDirection(x, y), r = rays.radiance(cam.position, d, 0.0, HUGE_VAL);
      double t0, t1;
      glm::dvec3 q(0.0);
      if (rays.span(cam.position, d, t0, t1))
        for (const GlowEmitter& e : rays.emitters)
          q += rays.intensity * e.colour *
               glowQuadrature(e, rays.eps, cam.position, d, t0, t1).value;
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(std::isfinite(r[k]));
        if (q[k] > 0.0)
          worst = std::max(worst, std::abs(r[k] - q[k]) / q[k]);
        else
          EXPECT_EQ(r[k], 0.0);
      }
    }
  std::printf("glow reference pixels vs quadrature: worst relative error %.2e (bound 1e-6)\n",
              worst);
  EXPECT_LE(worst, 1e-6);
}

// Sort-last: each brick integrates only its box; the bricks' sums over d^3 bricks are the whole.
TEST(GlowReference, BricksAddUpToTheWhole) {
  const Box3 box{glm::dvec3(-2.0), glm::dvec3(2.0)};
  const GlowSpec g = spec();
  GlowRays whole(g, box, 0);
  Camera cam = camera();
  for (int d = 1; d <= 3; ++d) {
    std::vector<GlowRays> bricks;
    for (int k = 0; k < d; ++k)
      for (int j = 0; j < d; ++j)
        for (int i = 0; i < d; ++i) {
          glm::dvec3 lo = box.lo + (box.hi - box.lo) * glm::dvec3(i, j, k) / double(d);
          glm::dvec3 hi = box.lo + (box.hi - box.lo) * glm::dvec3(i + 1, j + 1, k + 1) / double(d);
          bricks.emplace_back(g, Box3{lo, hi}, 0);
        }
    double worst = 0.0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        glm::dvec3 dir = cam.rayDirection(x, y), sum(0.0),
                   all = whole.radiance(cam.position, dir, 0.0, HUGE_VAL);
        for (const GlowRays& b : bricks) sum += b.radiance(cam.position, dir, 0.0, HUGE_VAL);
        for (int k = 0; k < 3; ++k)
          if (all[k] > 0.0) worst = std::max(worst, std::abs(sum[k] - all[k]) / all[k]);
      }
    std::printf("glow over %d^3 bricks vs the whole box: worst relative difference %.2e\n", d,
                worst);
    EXPECT_LE(worst, 1e-12) << d;
  }
}

// A black absorbing volume of constant extinction tau: the reference's glow (each step's exact
// integral times the transmittance at its middle) against tanh-sinh of E(s) T(s) along the ray.
// Within a step T(s) / T(mid) lies in [exp(-tau h / 2), exp(tau h / 2)], so the error is at most
// (exp(tau h / 2) - 1) times the glow inside the volume (rigorous), plus the closed form's 1e-6.
TEST(GlowReference, DimmedByTheVolume) {
  WholeVolume vol;
  vol.grid.dims = {9, 9, 9};
  vol.grid.spacing = glm::dvec3(0.25);  // box [-1, 1]^3
  vol.samples.assign(9 * 9 * 9, 0.5f);
  TransferFunction tf({{0.0, 0, 0, 0, 0.4}, {1.0, 0, 0, 0, 0.4}}, 0.0, 1.0, 1.0);
  const double tau = tf.extinction(0.5), h = 0.25 / 16;
  const Box3 glow_box{glm::dvec3(-2.0), glm::dvec3(2.0)};
  GlowRays rays(spec(), glow_box, 0);
  Camera cam = camera();
  ImageF img = renderReference(vol, tf, cam, h, 1, Shading{}, &rays);
  const Box3 vbox = vol.grid.worldBox();
  boost::math::quadrature::tanh_sinh<double> ts(15);
  double worst = 0.0;
  const double bound = std::expm1(tau * h / 2) + 1e-6;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const glm::dvec3 o = cam.position, d = cam.rayDirection(x, y);
      double g0, g1, v0 = HUGE_VAL, v1 = HUGE_VAL;
      if (!rays.span(o, d, g0, g1)) continue;
      if (intersectRayBox(o, d, vbox, v0, v1))
        v0 = std::max(v0, 0.0);
      else
        v0 = v1 = HUGE_VAL;  // (a miss leaves them unspecified)
      auto T = [&](double s) { return s <= v0 ? 1.0 : std::exp(-tau * (std::min(s, v1) - v0)); };
      // Pieces cut at the volume's faces and wherever the field has a jump or a peak.
      std::vector<double> cuts{g0, g1, v0, v1};
      for (const GlowEmitter& e : rays.emitters) {
        const glm::dvec3 w = o - e.centre;
        const double ud = glm::dot(d, e.direction);
        if (ud != 0.0) cuts.push_back(-glm::dot(w, e.direction) / ud);
        cuts.push_back(-glm::dot(w, d));
        const glm::dvec3 qc = d - ud * e.direction, wc = w - glm::dot(w, e.direction) * e.direction;
        if (glm::dot(qc, qc) > 0.0) cuts.push_back(-glm::dot(wc, qc) / glm::dot(qc, qc));
      }
      std::sort(cuts.begin(), cuts.end());
      glm::dvec3 exact(0.0);
      for (size_t i = 0; i + 1 < cuts.size(); ++i) {
        const double a = std::max(cuts[i], g0), b = std::min(cuts[i + 1], g1);
        if (!(b - a > 1e-12)) continue;
        for (const GlowEmitter& e : rays.emitters)
          exact += rays.intensity * e.colour *
                   ts.integrate([&](double s) { return glowField(e, rays.eps, o + s * d) * T(s); },
                                a, b, 1e-12);
      }
      for (int k = 0; k < 3; ++k) {
        const double r = img.px[4 * (size_t(y) * cam.width + x) + k];
        // The image is float: its rounding (6e-8) is below the bound by far.
        if (exact[k] > 0.0) worst = std::max(worst, std::abs(r - exact[k]) / exact[k]);
        if (exact[k] > 0.0 && std::abs(r - exact[k]) > bound * exact[k])
          ADD_FAILURE() << "pixel " << x << ", " << y << " channel " << k << ": reference " << r
                        << " exact " << exact[k];
      }
    }
  std::printf(
      "glow in an absorbing volume (tau %.3g, step %.4g): worst relative error %.2e (bound %.2e)\n",
      tau, h, worst, bound);
  EXPECT_LE(worst, bound);
  EXPECT_GT(worst, 0.0);  // the comparison is live: the volume does dim the glow
}

// The hard rays rendered: a camera at M (every ray through it), on the axis looking along it and
// across it, in the dividing plane looking along it; eps down to 1e-9. Every pixel finite, and
// each against quadrature on its own ray at the image's centre.
TEST(GlowReference, HardCamerasGiveFinitePixels) {
  struct View {
    glm::dvec3 position, look_at;
  };
  const glm::dvec3 m{0.1, -0.2, 0.3};
  const std::vector<View> views = {
      {m, m + glm::dvec3(0, 0, -1)},                           // at M
      {m + glm::dvec3(1.5, 0, 0), m + glm::dvec3(3, 0, 0)},    // on the axis, looking along it
      {m + glm::dvec3(1.5, 0, 0), m},                          // on the axis, looking back at M
      {m + glm::dvec3(0, 0, 1.5), m + glm::dvec3(0, 0.5, 0)},  // in the plane, looking along it
      {m + glm::dvec3(0, 0, 5), m},                            // outside, the beam across the view
  };
  for (double eps : {1e-9, 1e-3}) {
    char eps_text[32];
    std::snprintf(eps_text, sizeof eps_text, "%g", eps);
    for (const View& v : views) {
      Scene s =
          parse(kGlowOnly,
                {"image.width=33", "image.height=33", std::string("glow.core_radius=") + eps_text,
                 "glow.emitters=[{center: [0.1, -0.2, 0.3], direction: [1, 0, 0], a: 1, b: 1}]"});
      FrameReference ref(s, 1);
      Camera cam = s.camera;
      cam.position = v.position;
      cam.look_at = v.look_at;
      cam.up = std::abs(glm::normalize(v.look_at - v.position).y) > 0.9 ? glm::dvec3(1, 0, 0)
                                                                        : glm::dvec3(0, 1, 0);
      ImageF img = ref.render(cam);
      for (float p : img.px) ASSERT_TRUE(std::isfinite(p)) << eps;
      const glm::dvec3 d = cam.rayDirection(16, 16);
      GlowRays rays(s.glow, *s.glow.box, 0);
      double t0, t1;
      ASSERT_TRUE(rays.span(cam.position, d, t0, t1));
      const double q = glowQuadrature(rays.emitters[0], eps, cam.position, d, t0, t1).value;
      EXPECT_NEAR(img.px[4 * (16 * 33 + 16)], q, 1e-6 * q) << eps;  // float image: 6e-8
    }
  }
}

}  // namespace
}  // namespace sortlast
