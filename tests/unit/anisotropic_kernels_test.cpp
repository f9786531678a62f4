// The smoothed anisotropic kernels (io/anisotropic_kernels.h), the surface roughness figure
// (reference/surface_roughness.h) and the reference's anisotropic field: shapes on known
// arrangements, the mass normalisation, subset invariance, degenerate inputs, invalid keys.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "io/anisotropic_kernels.h"
#include "io/particles.h"
#include "scene/scene.h"
#include "reference/surface_roughness.h"
#include "input_error_of.h"
#include "reference/metaball_reference.h"

namespace sortlast {
namespace {

constexpr double kH = 0.6;

bool finite(const ParticleKernel& k) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      if (!std::isfinite(k.a[c][r])) return false;
  return std::isfinite(k.c) && std::isfinite(k.reach) && k.reach > 0 && k.c > 0 && std::isfinite(k.rho);
}

// Semi-axis length (units of h) along unit direction v of the support |A r| <= h, for v an
// eigenvector of A: 1 / |A v|.
double axisAlong(const ParticleKernel& k, glm::vec3 v) { return 1.0 / glm::length(k.a * v); }

// The parameters as a scene's particles.anisotropic.* keys (their ranges are the key table's).
std::vector<std::string> sceneKeysOf(const AnisotropicParams& p) {
  std::vector<std::string> out;
  for (auto [key, v] :
       {std::pair{"splash_scale", p.splash_scale}, std::pair{"surface_scale", p.surface_scale},
        std::pair{"rho_splash", p.rho_splash}, std::pair{"rho_surface", p.rho_surface},
        std::pair{"neighbourhood", p.neighbourhood},
        std::pair{"max_axis_ratio", p.max_axis_ratio}}) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", v);
    out.push_back(std::string("particles.anisotropic.") + key + "=" +
                  (std::isnan(v) ? ".nan" : text));
  }
  return out;
}

std::vector<glm::vec3> plane(int n, float a) {
  std::vector<glm::vec3> ps;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) ps.push_back({a * float(x), a * float(y), 0.0f});
  return ps;
}

TEST(AnisotropicKernels, LoneParticleIsTheRoundMetaballOfItsSplashRadius) {
  AnisotropicParams p;
  p.splash_scale = 0.8;
  auto k = computeAnisotropicKernels({{1.0f, 2.0f, 3.0f}}, kH, p);
  ASSERT_EQ(k.size(), 1u);
  EXPECT_EQ(k[0].s, 0.0f);
  EXPECT_EQ(k[0].rho, 1.0f);
  EXPECT_EQ(k[0].c, 1.0f);  // R = R_0: no normalisation
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_EQ(k[0].a[c][r], c == r ? float(1.0 / 0.8) : 0.0f);
  EXPECT_NEAR(k[0].reach, 0.8 * kH, 1e-5 * kH);
}

TEST(AnisotropicKernels, APlaneOfParticlesGivesDiscsOfTheMaximumAxisRatio) {
  AnisotropicParams p;  // h = 2 spacings: an inner particle has rho = 1 + 4 x 0.42 + 4 x 0.13 + 4 x 0.02 > 3
  auto ps = plane(9, float(kH / 2));
  auto k = computeAnisotropicKernels(ps, kH, p);
  const ParticleKernel& mid = k[4 * 9 + 4];
  EXPECT_EQ(mid.s, 1.0f);
  double in_plane = axisAlong(mid, {1, 0, 0}), normal = axisAlong(mid, {0, 0, 1});
  EXPECT_NEAR(axisAlong(mid, {0, 1, 0}), in_plane, 1e-5);
  // Directions all in the plane: sigma = (1.5, 1.5, 0) -> clamped to 1.5 / k^2 across it.
  EXPECT_NEAR(in_plane / normal, p.max_axis_ratio, 1e-4);
  EXPECT_NEAR(in_plane, p.surface_scale * std::sqrt(1.5), 1e-4);
}

TEST(AnisotropicKernels, EveryKernelCarriesTheMassOfTheReferenceSphere) {
  // Integral of C P(|A r|) = C / det A x integral of P(|u|): equal to the sphere of R_0 when
  // C / det A = R_0^3 (det A in units where the round kernel of radius R has det A = R^-3).
  AnisotropicParams p;
  p.splash_scale = 0.9;
  auto ps = plane(7, float(kH / 2));
  ps.push_back({0.0f, 0.0f, 5.0f});  // a lone one too
  ps.push_back({0.0f, 0.0f, 5.0f + float(kH / 3)});
  for (const ParticleKernel& k : computeAnisotropicKernels(ps, kH, p)) {
    ASSERT_TRUE(finite(k));
    double det = std::abs(glm::determinant(glm::dmat3(k.a)));
    EXPECT_NEAR(k.c / det, std::pow(p.splash_scale, 3), 2e-5);
  }
}

TEST(AnisotropicKernels, AKernelDependsOnlyOnItsNeighbourhoodBitForBit) {
  AnisotropicParams p;
  std::vector<glm::vec3> all;
  for (int i = 0; i < 400; ++i)  // a jittered block, deterministic
    all.push_back({float(i % 8) * 0.31f + 0.05f * float((i * 7) % 5), float((i / 8) % 7) * 0.29f,
                   float(i / 56) * 0.33f + 0.03f * float((i * 3) % 4)});
  auto full = computeAnisotropicKernels(all, kH, p);
  // The particles within h_n of particle 200, plus a few unrelated ones, in global order.
  std::vector<glm::vec3> subset;
  size_t at = 0;
  for (size_t i = 0; i < all.size(); ++i)
    if (glm::length(all[i] - all[200]) < 1.2 * kH * p.neighbourhood || i % 37 == 0) {
      if (i == 200) at = subset.size();
      subset.push_back(all[i]);
    }
  auto part = computeAnisotropicKernels(subset, kH, p);
  EXPECT_EQ(std::memcmp(&full[200], &part[at], sizeof(ParticleKernel)), 0);
  // With smoothed centres too (the centre is a sum over the same neighbours).
  p.position_smoothing = 0.9;
  full = computeAnisotropicKernels(all, kH, p);
  part = computeAnisotropicKernels(subset, kH, p);
  EXPECT_EQ(std::memcmp(&full[200], &part[at], sizeof(ParticleKernel)), 0);
}

TEST(AnisotropicKernels, PositionSmoothingMovesTheCentreTowardsTheNeighboursMean) {
  // Two particles h_n / 2 apart: each one's weighted mean is (1 c_i + g c_j) / (1 + g),
  // g = (1 - 1/4)^3; lambda = 0 keeps the particle's own position bit for bit.
  AnisotropicParams p;
  const float d = float(0.5 * kH * p.neighbourhood);
  std::vector<glm::vec3> ps = {{1.0f, 2.0f, 3.0f}, {1.0f + d, 2.0f, 3.0f}};
  auto k0 = computeAnisotropicKernels(ps, kH, p);
  EXPECT_EQ(k0[0].centre, ps[0]);
  EXPECT_EQ(k0[1].centre, ps[1]);
  p.position_smoothing = 0.6;
  auto k = computeAnisotropicKernels(ps, kH, p);
  const double g = 0.75 * 0.75 * 0.75, shift = 0.6 * g / (1.0 + g) * d;
  EXPECT_NEAR(k[0].centre.x, 1.0 + shift, 1e-6);
  EXPECT_NEAR(k[1].centre.x, 1.0 + d - shift, 1e-6);
  EXPECT_EQ(k[0].centre.y, 2.0f);
  // The reach bound covers the field around the moved centre.
  for (const ParticleKernel& q : k)
    EXPECT_LE(glm::length(glm::dvec3(q.centre) - glm::dvec3(ps[&q - k.data()])) + q.reach,
              anisotropicReachBound(p) * kH);
}

TEST(AnisotropicKernels, DegenerateInputsGiveFiniteKernels) {
  AnisotropicParams p;
  // Coincident particles: dense, but no direction: spheres of R_surface.
  std::vector<glm::vec3> same(10, glm::vec3(1.0f, 1.0f, 1.0f));
  for (const ParticleKernel& k : computeAnisotropicKernels(same, kH, p)) {
    ASSERT_TRUE(finite(k));
    EXPECT_EQ(k.s, 1.0f);
    EXPECT_NEAR(axisAlong(k, {1, 0, 0}), p.surface_scale, 1e-6);
    EXPECT_NEAR(axisAlong(k, {0, 1, 0}), p.surface_scale, 1e-6);
  }
  // A line (rank-1 covariance): a cigar of the maximum ratio, never a needle.
  std::vector<glm::vec3> line;
  for (int i = 0; i < 20; ++i) line.push_back({0.1f * float(i), 0.0f, 0.0f});
  auto kl = computeAnisotropicKernels(line, kH, p);
  for (const ParticleKernel& k : kl) ASSERT_TRUE(finite(k));
  const ParticleKernel& m = kl[10];
  ASSERT_EQ(m.s, 1.0f);
  EXPECT_NEAR(axisAlong(m, {1, 0, 0}) / axisAlong(m, {0, 1, 0}), p.max_axis_ratio, 1e-3);
  // Huge and tiny parameters: finite everywhere.
  auto mixed = line;
  mixed.insert(mixed.end(), same.begin(), same.end());
  mixed.push_back({50.0f, 0.0f, 0.0f});
  for (double scale : {1.0 / 64, 8.0})
    for (double hn : {1e-6, 8.0})
      for (double ratio : {1.0, 100.0})
        for (auto rho : {std::pair{0.0, 1e-9}, std::pair{1e8, 1e9}}) {
          AnisotropicParams q{scale, 8.0 / 64 / scale, rho.first, rho.second, hn, ratio};
          EXPECT_EQ(loadScene("", sceneKeysOf(q)).particles.anisotropic, q);  // the keys' extremes
          for (const ParticleKernel& k : computeAnisotropicKernels(mixed, kH, q)) {
            ASSERT_TRUE(finite(k)) << scale << " " << hn << " " << ratio << " " << rho.first;
            EXPECT_LE(k.reach, anisotropicReachBound(q) * kH);
          }
        }
}

TEST(AnisotropicKernels, InvalidParametersNameTheirKey) {
  auto err = [](auto change) {
    AnisotropicParams p;
    change(p);
    return inputErrorOf([&] { loadScene("", sceneKeysOf(p)); });
  };
  EXPECT_NE(err([](auto& p) { p.splash_scale = 0; }).find("particles.anisotropic.splash_scale"), std::string::npos);
  EXPECT_NE(err([](auto& p) { p.surface_scale = NAN; }).find("particles.anisotropic.surface_scale"), std::string::npos);
  EXPECT_NE(err([](auto& p) { p.neighbourhood = 20; }).find("particles.anisotropic.neighbourhood"), std::string::npos);
  EXPECT_NE(err([](auto& p) { p.rho_splash = -1; }).find("particles.anisotropic.rho_splash"), std::string::npos);
  EXPECT_NE(err([](auto& p) { p.rho_surface = 1; }).find("particles.anisotropic.rho_surface"), std::string::npos);
  EXPECT_NE(err([](auto& p) { p.max_axis_ratio = 0.5; }).find("particles.anisotropic.max_axis_ratio"), std::string::npos);
}

TEST(AnisotropicReference, RoundKernelsGiveTheRoundField) {
  std::vector<glm::vec3> ps = {{0, 0, 0}, {0.3f, 0, 0}, {0, 0.4f, 0.1f}};
  MetaballModel round{{}, kH, 0.7, {}};
  for (auto& p : ps) round.positions.emplace_back(p);
  MetaballModel aniso = round;
  aniso.kernels.assign(ps.size(), ParticleKernel{});  // A = I, C = 1, reach 1 ... set below
  for (auto& k : aniso.kernels) k.reach = float(kH * (1 + 1e-6));
  MetaballField a(round), b(aniso);
  for (glm::dvec3 x : {glm::dvec3(0.1, 0.1, 0), glm::dvec3(-0.3, 0.2, 0.1), glm::dvec3(0.2, 0.5, 0)}) {
    EXPECT_DOUBLE_EQ(a.field(x), b.field(x));
    EXPECT_LT(glm::length(a.gradient(x) - b.gradient(x)), 1e-12);
  }
}

TEST(AnisotropicReference, AStretchedKernelMovesTheSurfaceAlongItsAxis) {
  // One particle, A = diag(1/2, 1, 1), C = 1: the surface lies at 2 h (1 - T) along x and
  // h (1 - T) along y.
  MetaballModel m{{glm::dvec3(0.0)}, kH, 0.75, {ParticleKernel{}}};
  m.kernels[0].a = glm::mat3(glm::vec3(0.5f, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1));
  m.kernels[0].reach = float(2 * kH * (1 + 1e-6));
  MetaballField f(m);
  Box3 all{glm::dvec3(-10), glm::dvec3(10)};
  RayHit hx = f.firstHit({5, 0, 0}, {-1, 0, 0}, all), hy = f.firstHit({0, 5, 0}, {0, -1, 0}, all);
  ASSERT_TRUE(hx.hit() && hy.hit());
  EXPECT_NEAR(5 - hx.t, 2 * kH * 0.25, 1e-9);
  EXPECT_NEAR(5 - hy.t, kH * 0.25, 1e-9);
  EXPECT_NEAR(hx.normal.x, 1.0, 1e-9);
}

SurfaceImage planeImage(int n, double tilt_per_pixel_deg) {
  SurfaceImage img(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      double a = tilt_per_pixel_deg * x * 3.14159265358979323846 / 180.0;
      img.t[size_t(y) * n + x] = 10.0f;
      img.normal[size_t(y) * n + x] = glm::vec3(std::sin(a), 0.0, std::cos(a));
    }
  return img;
}

TEST(SurfaceRoughness, MeasuresTheAngleBetweenNeighbouringNormals) {
  Roughness flat = surfaceRoughness(planeImage(16, 0.0), {});
  EXPECT_EQ(flat.pairs, 2 * 16 * 15);
  EXPECT_LT(flat.rms_deg, 1e-3);
  // Normals turning 1 degree a pixel along x, none along y: half the pairs 1, half 0.
  Roughness bent = surfaceRoughness(planeImage(16, 1.0), {});
  EXPECT_NEAR(bent.rms_deg, std::sqrt(0.5), 1e-3);
  EXPECT_NEAR(bent.mean_deg, 0.5, 1e-3);
  // A depth jump cuts the pair; misses are left out; a region restricts.
  SurfaceImage img = planeImage(16, 0.0);
  for (int y = 0; y < 16; ++y) img.t[size_t(y) * 16 + 15] = 20.0f, img.normal[size_t(y) * 16 + 15] = {1, 0, 0};
  EXPECT_LT(surfaceRoughness(img, {}).rms_deg, 1e-3);
  RoughnessOptions region;
  region.x0 = 2, region.y0 = 2, region.x1 = 6, region.y1 = 6;
  EXPECT_EQ(surfaceRoughness(img, region).pairs, 2 * 4 * 3);
  region.x0 = 20;
  EXPECT_NE(inputErrorOf([&] { surfaceRoughness(img, region); }).find("region"), std::string::npos);
}

TEST(SurfaceRoughness, CountsConnectedPiecesOfTheSurface) {
  // The plane with its depth-jumped last column: 2 pieces; misses split it further; a piece
  // smaller than min_piece_pixels (a lone pixel) is not counted.
  SurfaceImage img = planeImage(16, 0.0);
  EXPECT_EQ(surfaceRoughness(img, {}).pieces, 1);
  for (int y = 0; y < 16; ++y) img.t[size_t(y) * 16 + 15] = 20.0f;
  EXPECT_EQ(surfaceRoughness(img, {}).pieces, 2);
  for (int x = 0; x < 15; ++x) img.t[size_t(8) * 16 + x] = INFINITY;  // a missed row: 3 pieces
  EXPECT_EQ(surfaceRoughness(img, {}).pieces, 3);
  for (int x = 0; x < 15; ++x)
    for (int y = 9; y < 16; ++y) img.t[size_t(y) * 16 + x] = (x == 4 && y == 12) ? 10.0f : INFINITY;
  EXPECT_EQ(surfaceRoughness(img, {}).pieces, 2);  // the lone pixel left of the column is not a piece
}

}  // namespace

// particles.smoothing: auto. A cubic lattice of spacing s has 6 neighbours at s, 12 at s sqrt(2),
// 8 at s sqrt(3): at s = 0.7 h an inner particle has 6 + 12 = 18 within h, at s = 1.1 h none.
TEST(AutoSmoothing, CountsNeighboursWithinHAndChoosesBySpacing) {
  auto lattice = [](float s) {
    std::vector<glm::vec3> ps;
    for (int z = 0; z < 12; ++z)
      for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 12; ++x) ps.emplace_back(x * s, y * s, z * s);
    return ps;
  };
  const double h = 1.0;
  NeighbourCount dense = countNeighbours(lattice(0.7f), h), sparse = countNeighbours(lattice(1.1f), h);
  EXPECT_EQ(dense.sampled, 12.0 * 12 * 12);
  const double mean = dense.neighbours / dense.sampled;
  EXPECT_GT(mean, 12.0);  // 18 inside, fewer on the faces, edges and corners
  EXPECT_LT(mean, 18.0);
  EXPECT_EQ(sparse.neighbours, 0.0);
  // Strided sampling: every 8th particle (max_sampled 216) gives a mean in the same range.
  NeighbourCount strided = countNeighbours(lattice(0.7f), h, 216);
  EXPECT_EQ(strided.sampled, 216.0);
  EXPECT_GT(strided.neighbours / strided.sampled, 12.0);

  ParticleDesc d;
  d.smoothing = Smoothing::kAuto;
  resolveAutoSmoothing(d, dense);
  EXPECT_EQ(d.smoothing, Smoothing::kAnisotropic);
  EXPECT_NE(d.smoothing_reason.find("auto: anisotropic"), std::string::npos) << d.smoothing_reason;
  d.smoothing = Smoothing::kAuto;
  resolveAutoSmoothing(d, sparse);
  EXPECT_EQ(d.smoothing, Smoothing::kNone);
  EXPECT_NE(d.smoothing_reason.find("auto: none"), std::string::npos) << d.smoothing_reason;
  // Round-only settings: billboards and in situ give none however dense.
  d.smoothing = Smoothing::kAuto;
  d.method = ParticleMethod::kBillboards;
  resolveAutoSmoothing(d, dense);
  EXPECT_EQ(d.smoothing, Smoothing::kNone);
  d.smoothing = Smoothing::kAuto;
  d.method = ParticleMethod::kGrid;
  resolveAutoSmoothing(d, dense, true);
  EXPECT_EQ(d.smoothing, Smoothing::kNone);
  // An explicit choice stands.
  d.smoothing = Smoothing::kAnisotropic;
  resolveAutoSmoothing(d, sparse);
  EXPECT_EQ(d.smoothing, Smoothing::kAnisotropic);
  EXPECT_EQ(d.smoothing_reason, "set: particles.smoothing: anisotropic");
}

}  // namespace sortlast
