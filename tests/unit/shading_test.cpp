// Gradient shading (transfer/shading.h): the model, the reference's gradient, and the scene keys.
#include "transfer/shading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/scene.h"
#include "reference/reference.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

const std::array<double, 3> kColour{0.8, 0.5, 0.2};
const Shading kOn{true, 0.3, 0.7, 0.2, 20.0};

TEST(Shading, HeadlightBlinnPhongTwoSided) {
  const glm::dvec3 dir = glm::normalize(glm::dvec3(1.0, 2.0, -2.0));
  const double flat = 1.0;
  // Gradient along the ray, either way: c (ka + kd) + ks, clamped to 1.
  for (double sign : {1.0, -1.0}) {
    auto c = shadeSample(kColour, sign * 5.0 * dir, dir, kOn, flat);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], std::min(1.0, kColour[k] * 1.0 + 0.2), 1e-12) << k;
  }
  // Across the ray: ambient only (cos 0, and 0^p = 0).
  const glm::dvec3 across = glm::normalize(glm::cross(dir, glm::dvec3(0.0, 0.0, 1.0)));
  auto c = shadeSample(kColour, 3.0 * across, dir, kOn, flat);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 0.3 * kColour[k], 1e-12) << k;
  // At 60 degrees: cos 1/2.
  const glm::dvec3 g = 0.5 * dir + std::sqrt(0.75) * across;
  c = shadeSample(kColour, 4.0 * g, dir, kOn, flat);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(c[k], kColour[k] * (0.3 + 0.35) + 0.2 * std::pow(0.5, 20.0), 1e-12) << k;
}

TEST(Shading, FlatRegionsStayUnshadedAndTheWeightIsContinuous) {
  const glm::dvec3 dir(0.0, 0.0, 1.0);
  const double flat = 0.01;
  // At or below the floor (zero included): the colour itself, bit for bit.
  for (double len : {0.0, 0.005, 0.01})
    EXPECT_EQ(shadeSample(kColour, glm::dvec3(0.0, 0.0, len), dir, kOn, flat), kColour) << len;
  // From twice the floor: fully shaded; between: the linear mix.
  auto full = shadeSample(kColour, glm::dvec3(0.0, 0.0, 0.02), dir, kOn, flat);
  auto far = shadeSample(kColour, glm::dvec3(0.0, 0.0, 7.0), dir, kOn, flat);
  auto half = shadeSample(kColour, glm::dvec3(0.0, 0.0, 0.015), dir, kOn, flat);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(full[k], far[k], 1e-15);
    EXPECT_NEAR(half[k], 0.5 * (kColour[k] + full[k]), 1e-12);
  }
  // The floor: 0.001 of the range per smallest voxel spacing; a zero range counts as 1.
  EXPECT_DOUBLE_EQ(flatGradient(10.0, 265.0, {2.0, 0.5, 4.0}), 1e-3 * 255.0 / 0.5);
  EXPECT_DOUBLE_EQ(flatGradient(3.0, 3.0, {1.0, 1.0, 1.0}), 1e-3);
}

TEST(Shading, IdentityModelReturnsTheColourExactly) {
  // ka = 1, kd = ks = 0: c' = c at any gradient (tests/mpi/shading.sh onoff relies on it in GL).
  const Shading identity{true, 1.0, 0.0, 0.0, 20.0};
  const glm::dvec3 dir = glm::normalize(glm::dvec3(0.3, -0.4, 1.0));
  for (const glm::dvec3& g : {glm::dvec3(1.0, 2.0, 3.0), glm::dvec3(0.0, 0.0, 1e-9), dir})
    EXPECT_EQ(shadeSample(kColour, g, dir, identity, 1e-6), kColour);
}

// A linear field f = 2x + 3y - z of sample indices, on a grid with unequal spacing.
WholeVolume linearVolume() {
  WholeVolume vol;
  vol.grid.dims = {5, 6, 7};
  vol.grid.spacing = {0.5, 2.0, 1.0};
  for (int z = 0; z < 7; ++z)
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 5; ++x) vol.samples.push_back(float(2 * x + 3 * y - z));
  return vol;
}

TEST(Shading, ReferenceGradientIsTheWorldCentralDifference) {
  WholeVolume vol = linearVolume();
  // Inside: exact, per world unit (index slope / spacing), also between samples.
  for (const glm::dvec3& u : {glm::dvec3(2.0, 2.0, 3.0), glm::dvec3(1.3, 3.7, 4.5)}) {
    glm::dvec3 g = vol.gradient(u);
    EXPECT_NEAR(g.x, 2.0 / 0.5, 1e-12);
    EXPECT_NEAR(g.y, 3.0 / 2.0, 1e-12);
    EXPECT_NEAR(g.z, -1.0 / 1.0, 1e-12);
  }
  // On a face of the grid the index clamps: a one-sided difference, half the slope.
  glm::dvec3 g = vol.gradient({0.0, 5.0, 3.0});
  EXPECT_NEAR(g.x, 0.5 * 2.0 / 0.5, 1e-12);
  EXPECT_NEAR(g.y, 0.5 * 3.0 / 2.0, 1e-12);
  EXPECT_NEAR(g.z, -1.0, 1e-12);
}

TEST(Shading, ReferenceShadesColourNotOpacity) {
  WholeVolume vol = linearVolume();
  TransferFunction tf({{0.0, 1.0, 0.6, 0.2, 0.1}, {1.0, 0.2, 0.6, 1.0, 0.3}}, -6.0, 23.0, 0.5);
  Camera cam;
  cam.position = {1.0, 2.0, 9.0};
  cam.look_at = {0.0, 0.0, 0.0};
  cam.width = 12;
  cam.height = 10;
  cam.fov_deg = 40.0;
  const double step = 0.5 / 8;
  ImageF off = renderReference(vol, tf, cam, step, 2);
  ImageF identity = renderReference(vol, tf, cam, step, 2, Shading{true, 1.0, 0.0, 0.0, 20.0});
  EXPECT_EQ(identity.px, off.px);
  ImageF on = renderReference(vol, tf, cam, step, 2, kOn);
  double most = 0.0;
  for (size_t i = 0; i < on.px.size(); i += 4) {
    EXPECT_EQ(on.px[i + 3], off.px[i + 3]) << i / 4;  // alpha: the same bits
    for (int k = 0; k < 3; ++k) most = std::max(most, std::abs(double(on.px[i + k]) - off.px[i + k]));
  }
  EXPECT_GT(most, 0.05);  // and the colours do change
}

TEST(Shading, SceneKeys) {
  Scene s = loadScene("", {});
  EXPECT_FALSE(s.render.shading.enabled);
  const Shading d;
  EXPECT_EQ(s.render.shading.ambient, d.ambient);
  EXPECT_EQ(s.render.shading.diffuse, d.diffuse);
  EXPECT_EQ(s.render.shading.specular, d.specular);
  EXPECT_EQ(s.render.shading.shininess, d.shininess);
  s = loadScene("", {"render.shading=true", "render.shading_ambient=0.1", "render.shading_diffuse=0.9",
                     "render.shading_specular=0.5", "render.shading_shininess=64"});
  EXPECT_TRUE(s.render.shading.enabled);
  EXPECT_EQ(s.render.shading.ambient, 0.1);
  EXPECT_EQ(s.render.shading.diffuse, 0.9);
  EXPECT_EQ(s.render.shading.specular, 0.5);
  EXPECT_EQ(s.render.shading.shininess, 64.0);
  for (const char* key : {"render.shading", "render.shading_ambient", "render.shading_diffuse",
                          "render.shading_specular", "render.shading_shininess"})
    EXPECT_TRUE(isFrameKey(key)) << key;
  for (std::string bad : {"render.shading_ambient=-0.1", "render.shading_diffuse=.nan",
                          "render.shading_specular=1000", "render.shading_shininess=0.5",
                          "render.shading=maybe"}) {
    std::string msg = inputErrorOf([&] { loadScene("", {bad}); });
    EXPECT_NE(msg.find(bad.substr(0, bad.find('='))), std::string::npos) << msg;
  }
  std::string msg = inputErrorOf([] {
    loadScene("", {"render.method=raycast", "adaptive.tolerance=5", "render.shading=true"});
  });
  EXPECT_NE(msg.find("render.shading"), std::string::npos) << msg;
  EXPECT_NE(msg.find("adaptive.tolerance"), std::string::npos) << msg;
}

}  // namespace
}  // namespace sortlast
