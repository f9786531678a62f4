// The metaball reference (reference/metaball_reference.h) against closed forms, the surface image
// file (io/surface_image.h), surface comparison (app/compare_surface.h), shading
// (transfer/metaball_shading.h) and the volume reference stopped by a surface (reference/reference.h).
#include "common/build_features.h"
#include "reference/metaball_reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <vector>

#include "common/error.h"
#include "transfer/metaball_shading.h"
#include "io/surface_image.h"
#include "app/compare_surface.h"
#include "reference/reference.h"
#include "app/reference_job.h"

namespace sortlast {
namespace {

constexpr double kH = 0.61, kT = 0.765625;  // the paper's constants
constexpr double kInf = std::numeric_limits<double>::infinity();

Box3 bigBox() { return {glm::dvec3(-10.0), glm::dvec3(10.0)}; }

Camera cameraAt(const glm::dvec3& pos, const glm::dvec3& look, int w, int h, double fov) {
  Camera c;
  c.position = pos;
  c.look_at = look;
  c.up = glm::dvec3(0.0, 1.0, 0.0);
  c.fov_deg = fov;
  c.width = w;
  c.height = h;
  return c;
}

// Ray-sphere intersection: the nearer t, or +inf.
double sphereHit(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& centre,
                 double radius) {
  glm::dvec3 oc = o - centre;
  double b = glm::dot(d, oc), c = glm::dot(oc, oc) - radius * radius, disc = b * b - c;
  return disc > 0.0 ? -b - std::sqrt(disc) : kInf;
}

double angleRad(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// Pixels whose 3x3 neighbourhood holds both hits and misses of `hit`: within about one pixel of
// the silhouette.
std::vector<bool> nearSilhouette(const std::vector<bool>& hit, int w, int h) {
  std::vector<bool> out(hit.size(), false);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          int nx = x + dx, ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < w && ny < h &&
              hit[size_t(ny) * w + nx] != hit[size_t(y) * w + x])
            out[size_t(y) * w + x] = true;
        }
  return out;
}

TEST(MetaballReference, OneParticleIsTheAnalyticSphere) {
  const glm::dvec3 p(0.013, -0.021, 0.007);
  const double radius = kH * (1.0 - kT);
  MetaballModel model{{p}, kH, kT};
  MetaballField field(model);
  Camera cam = cameraAt({0.2, 0.3, 1.0}, {0.0, 0.0, 0.0}, 96, 80, 20.0);
  SurfaceImage img = referenceSurface(model, cam, bigBox(), 3);
  ASSERT_EQ(img.width, 96);
  ASSERT_EQ(img.height, 80);

  std::vector<bool> analytic(size_t(cam.width) * cam.height);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      analytic[size_t(y) * cam.width + x] =
          std::isfinite(sphereHit(cam.position, cam.rayDirection(x, y), p, radius));
  std::vector<bool> edge = nearSilhouette(analytic, cam.width, cam.height);

  int hits = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      size_t i = size_t(y) * cam.width + x;
      glm::dvec3 d = cam.rayDirection(x, y);
      RayHit hit = field.firstHit(cam.position, d, bigBox());
      // The image is the per-ray result, rounded to float.
      EXPECT_EQ(img.hit(i), hit.hit()) << x << "," << y;
      if (hit.hit()) {
        EXPECT_EQ(img.t[i], float(hit.t)) << x << "," << y;
      }
      if (edge[i]) continue;
      ASSERT_EQ(hit.hit(), analytic[i]) << "pixel " << x << "," << y;
      if (!hit.hit()) continue;
      ++hits;
      double t = sphereHit(cam.position, d, p, radius);
      EXPECT_NEAR(hit.t, t, 1e-7 * kH) << "pixel " << x << "," << y;
      glm::dvec3 n = glm::normalize(cam.position + t * d - p);
      EXPECT_LT(angleRad(hit.normal, n), 1e-6) << "pixel " << x << "," << y;
      EXPECT_NEAR(glm::length(glm::dvec3(img.normal[i])), 1.0, 1e-6);
    }
  EXPECT_GT(hits, 2000);  // the disc is about 31 pixels in radius
}

TEST(MetaballReference, RayThroughTheCentreAndGrazingRays) {
  const glm::dvec3 p(0.1, 0.2, -0.3), o(0.1, 0.2, 1.7);
  const double radius = kH * (1.0 - kT);
  MetaballField field(MetaballModel{{p}, kH, kT});
  // Straight through the centre: the gradient there is 0 (defined so), but the hit is R in front.
  RayHit hit = field.firstHit(o, {0.0, 0.0, -1.0}, bigBox());
  ASSERT_TRUE(hit.hit());
  EXPECT_NEAR(hit.t, 2.0 - radius, 1e-7 * kH);
  EXPECT_LT(angleRad(hit.normal, {0.0, 0.0, 1.0}), 1e-9);
  EXPECT_EQ(field.gradient(p), glm::dvec3(0.0));
  EXPECT_NEAR(field.field(p), 1.0, 1e-15);
  // Tangent and nearly tangent rays: a hit, if any, is a true surface point with a unit normal.
  for (double off : {radius, radius * (1 - 1e-12), radius * (1 - 1e-6), radius * (1 + 1e-12)}) {
    RayHit g = field.firstHit(o + glm::dvec3(off, 0.0, 0.0), {0.0, 0.0, -1.0}, bigBox());
    if (!g.hit()) continue;
    EXPECT_NEAR(field.implicit(o + glm::dvec3(off, 0.0, 0.0) + g.t * glm::dvec3(0, 0, -1)), 0.0,
                1e-9);
    EXPECT_NEAR(glm::length(g.normal), 1.0, 1e-12);
    EXPECT_NEAR(g.t, 2.0, 1e-3 * kH);
  }
  // Far outside: a miss.
  EXPECT_FALSE(field.firstHit(o + glm::dvec3(kH, 0.0, 0.0), {0.0, 0.0, -1.0}, bigBox()).hit());
}

TEST(MetaballReference, EnteringTheClipBoxInsideTheSurfaceIsAMiss) {
  MetaballField field(MetaballModel{{glm::dvec3(0.0)}, kH, kT});
  const double radius = kH * (1.0 - kT);
  const glm::dvec3 o(0.0, 0.0, 2.0), d(0.0, 0.0, -1.0);
  Box3 front{{-1.0, -1.0, 0.05}, {1.0, 1.0, 1.0}}, back{{-1.0, -1.0, -1.0}, {1.0, 1.0, 0.05}};
  RayHit f = field.firstHit(o, d, front);
  ASSERT_TRUE(f.hit());
  EXPECT_NEAR(f.t, 2.0 - radius, 1e-7 * kH);
  EXPECT_FALSE(field.firstHit(o, d, back).hit());  // starts at z = 0.05, inside the sphere
  // A box wholly inside the surface, a box behind the camera, and an empty field: misses.
  EXPECT_FALSE(field.firstHit(o, d, Box3{{-1.0, -1.0, -0.05}, {1.0, 1.0, 0.05}}).hit());
  EXPECT_FALSE(field.firstHit(o, d, Box3{{-1.0, -1.0, 2.5}, {1.0, 1.0, 3.0}}).hit());
  EXPECT_FALSE(MetaballField(MetaballModel{{}, kH, kT}).firstHit(o, d, bigBox()).hit());

  // Over an image, a front and a back box split the full-box surface between them: each pixel
  // hits in at most one, at the full box's depth.
  Camera cam = cameraAt({1.2, 0.2, 0.3}, {0.0, 0.0, 0.0}, 64, 64, 24.0);  // the split is in view
  SurfaceImage all = referenceSurface({{glm::dvec3(0.0)}, kH, kT}, cam, bigBox(), 2);
  SurfaceImage a = referenceSurface({{glm::dvec3(0.0)}, kH, kT}, cam, front, 2);
  SurfaceImage b = referenceSurface({{glm::dvec3(0.0)}, kH, kT}, cam, back, 2);
  std::vector<bool> hit_all(all.t.size());
  for (size_t i = 0; i < all.t.size(); ++i) hit_all[i] = all.hit(i);
  std::vector<bool> edge = nearSilhouette(hit_all, cam.width, cam.height);
  int in_front = 0, in_back = 0;
  for (size_t i = 0; i < all.t.size(); ++i) {
    EXPECT_FALSE(a.hit(i) && b.hit(i)) << i;
    if (edge[i]) continue;
    EXPECT_EQ(all.hit(i), a.hit(i) || b.hit(i)) << i;
    if (a.hit(i)) {
      EXPECT_NEAR(a.t[i], all.t[i], 1e-6) << i;
      ++in_front;
    }
    if (b.hit(i)) {
      EXPECT_NEAR(b.t[i], all.t[i], 1e-6) << i;
      ++in_back;
    }
  }
  EXPECT_GT(in_front, 100);
  EXPECT_GT(in_back, 100);
}

// Every hit is on I = 0, and I < 0 at fine samples in front of it; the normal is -grad F / |grad F|
// at the hit (grad F from the field's own grid lookup, a second path to the same neighbours).
void checkSurfaceProperties(const MetaballModel& model, const Camera& cam, int min_hits) {
  MetaballField field(model);
  Box3 clip{glm::dvec3(-3.0), glm::dvec3(3.0)};
  SurfaceImage img = referenceSurface(model, cam, clip, 2);
  int hits = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      size_t i = size_t(y) * cam.width + x;
      if (!img.hit(i) || isSilhouettePixel(img, x, y)) continue;
      ++hits;
      glm::dvec3 d = cam.rayDirection(x, y);
      RayHit hit = field.firstHit(cam.position, d, clip);
      ASSERT_TRUE(hit.hit());
      EXPECT_NEAR(field.implicit(cam.position + hit.t * d), 0.0, 1e-9) << x << "," << y;
      double t0, t1;
      ASSERT_TRUE(intersectRayBox(cam.position, d, clip, t0, t1));
      for (double t = std::max(t0, 0.0); t < hit.t - 1e-7 * model.h; t += model.h / 512)
        ASSERT_LT(field.implicit(cam.position + t * d), 0.0) << x << "," << y << " t=" << t;
      glm::dvec3 g = field.gradient(cam.position + hit.t * d);
      EXPECT_LT(angleRad(hit.normal, -g / glm::length(g)), 1e-9) << x << "," << y;
    }
  EXPECT_GE(hits, min_hits);
}

TEST(MetaballReference, TwoParticlesHitTheLevelSet) {
  MetaballModel model{{{-0.12, 0.0, 0.0}, {0.13, 0.02, -0.01}}, kH, kT};
  checkSurfaceProperties(model, cameraAt({0.4, 0.5, 1.1}, {0.0, 0.0, 0.0}, 48, 40, 30.0), 300);
}

TEST(MetaballReference, ClusterHitsTheLevelSet) {
  // Many particles over many grid cells: any neighbour the ray's cell walk misses shows up as
  // I != 0 at the hit.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MetaballModel model{{}, 0.3, 0.6};
  for (int i = 0; i < 300; ++i) model.positions.push_back({u(rng), 0.5 * u(rng), u(rng)});
  checkSurfaceProperties(model, cameraAt({1.9, 1.7, 2.6}, {0.0, 0.0, 0.0}, 40, 40, 50.0), 400);
  // Axis-parallel rays (zero direction components) through the cluster.
  checkSurfaceProperties(model, cameraAt({0.0, 0.0, 2.9}, {0.0, 0.0, 0.0}, 9, 9, 40.0), 5);
}

TEST(MetaballReference, BadModelThrows) {
  EXPECT_THROW(MetaballField(MetaballModel{{glm::dvec3(0.0)}, 0.0, kT}), InputError);
  EXPECT_THROW(MetaballField(MetaballModel{{glm::dvec3(0.0)}, kH, 0.0}), InputError);
  EXPECT_THROW(MetaballField(MetaballModel{{glm::dvec3(0.0)}, std::nan(""), kT}), InputError);
  EXPECT_THROW(MetaballField(MetaballModel{{glm::dvec3(0.0, kInf, 0.0)}, kH, kT}), InputError);
  EXPECT_THROW(MetaballField(MetaballModel{{glm::dvec3(0.0), glm::dvec3(1e30)}, kH, kT}),
               InputError);
}

TEST(MetaballShading, HeadlightFormula) {
  const glm::dvec3 d(0.0, 0.0, -1.0), colour(0.6, 1.0, 0.2);
  glm::dvec4 facing = shadeMetaball(glm::dvec3(0.0, 0.0, 1.0), d, colour);
  EXPECT_EQ(facing, glm::dvec4(0.6, 1.0, 0.2, 1.0));
  glm::dvec4 side = shadeMetaball(glm::dvec3(1.0, 0.0, 0.0), d, colour);
  EXPECT_NEAR(side.x, 0.12, 1e-15);
  EXPECT_NEAR(side.y, 0.2, 1e-15);
  EXPECT_EQ(side.w, 1.0);
  EXPECT_EQ(shadeMetaball(glm::dvec3(0.0, 0.0, -1.0), d, colour), side);  // back faces: ambient
  EXPECT_EQ(shadeMetaball(glm::dvec3(0.0, 0.0, 1.0), d, glm::dvec3(2.0)),
            glm::dvec4(1.0));  // clamped

  Camera cam = cameraAt({0.0, 0.0, 1.0}, {0.0, 0.0, 0.0}, 2, 1, 30.0);
  SurfaceImage s(2, 1);
  s.t[0] = 1.0f;
  s.normal[0] = glm::vec3(-cam.rayDirection(0, 0));
  ImageRGBA8 img = shadeSurface(s, cam, colour);
  EXPECT_EQ(img.at(0, 0)[0], 153);
  EXPECT_EQ(img.at(0, 0)[1], 255);
  EXPECT_EQ(img.at(0, 0)[2], 51);
  EXPECT_EQ(img.at(0, 0)[3], 255);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(img.at(1, 0)[c], 0);
  EXPECT_THROW(shadeSurface(SurfaceImage(3, 1), cam, colour), InputError);
}

// Hand-made 6x5 surfaces. Reference: hits in the 4x3 block x 1..4, y 1..3, t = 2.
SurfaceImage block() {
  SurfaceImage s(6, 5);
  for (int y = 1; y <= 3; ++y)
    for (int x = 1; x <= 4; ++x) {
      s.t[size_t(y) * 6 + x] = 2.0f;
      s.normal[size_t(y) * 6 + x] = glm::vec3(0.0f, 0.0f, 1.0f);
    }
  return s;
}

TEST(CompareSurface, HolesExtrasDepthAndNormals) {
  SurfaceImage ref = block(), test = block();
  EXPECT_EQ(compareSurfaces(ref, test, false).holes, 0);
  EXPECT_EQ(compareSurfaces(ref, test, false).depth_max, 0.0);

  test.t[2 * 6 + 2] = kInf;                                     // hole, interior (2,2)
  test.t[1 * 6 + 1] = std::numeric_limits<float>::quiet_NaN();  // hole, corner of the block (1,1)
  test.t[0 * 6 + 0] = 5.0f;                                     // extra, away from the block (0,0)
  test.t[1 * 6 + 5] = 5.0f;                                     // extra, next to the block (5,1)
  test.t[2 * 6 + 3] = 2.5f;                                     // depth 0.5 at (3,2)
  test.t[3 * 6 + 3] = 1.9f;                                     // depth 0.1 at (3,3)
  test.normal[3 * 6 + 2] = glm::vec3(0.0f, 1.0f, 1.0f);         // 45 degrees at (2,3)

  SurfaceDifference d = compareSurfaces(ref, test, false);
  EXPECT_EQ(d.holes, 2);
  EXPECT_EQ(d.extra, 2);
  EXPECT_EQ(d.both, 10);
  EXPECT_EQ(d.edges_ignored, 0);
  EXPECT_EQ(d.first_hole_x, 1);
  EXPECT_EQ(d.first_hole_y, 1);
  EXPECT_EQ(d.first_extra_x, 0);
  EXPECT_EQ(d.first_extra_y, 0);
  EXPECT_NEAR(d.depth_max, 0.5, 1e-7);
  EXPECT_EQ(d.worst_depth_x, 3);
  EXPECT_EQ(d.worst_depth_y, 2);
  EXPECT_NEAR(d.depth_rms, std::sqrt((0.25 + 0.01) / 10.0), 1e-7);
  EXPECT_NEAR(d.normal_max_deg, 45.0, 1e-5);
  EXPECT_NEAR(d.normal_mean_deg, 4.5, 1e-6);
  EXPECT_EQ(d.worst_normal_x, 2);
  EXPECT_EQ(d.worst_normal_y, 3);

  // Silhouette pixels of the reference: the block's 10 border pixels and the 14 misses beside it.
  // Left: the image corners (the extra at (0,0) among them) and the block's interior (2,2), (3,2).
  EXPECT_TRUE(isSilhouettePixel(ref, 1, 1));
  EXPECT_TRUE(isSilhouettePixel(ref, 5, 1));
  EXPECT_FALSE(isSilhouettePixel(ref, 2, 2));
  EXPECT_FALSE(isSilhouettePixel(ref, 0, 0));
  SurfaceDifference e = compareSurfaces(ref, test, true);
  EXPECT_EQ(e.edges_ignored, 10 + 14);
  EXPECT_EQ(e.holes, 1);  // (2,2)
  EXPECT_EQ(e.extra, 1);  // (0,0)
  EXPECT_EQ(e.both, 1);   // (3,2)
  EXPECT_NEAR(e.depth_max, 0.5, 1e-7);
  EXPECT_EQ(e.normal_max_deg, 0.0);

  EXPECT_THROW(compareSurfaces(ref, SurfaceImage(5, 5), false), InputError);
}

TEST(SurfaceImage, ExrRoundTrip) {
  if (!build::kExr) GTEST_SKIP() << "this build has no OpenEXR (SORTLAST_WITH_EXR)";
  SurfaceImage s(7, 3);
  for (size_t i = 0; i < s.t.size(); i += 2) {
    s.t[i] = 0.1f * float(i) + 1e-3f;
    s.normal[i] = glm::normalize(glm::vec3(float(i), 1.0f, -2.0f));
  }
  std::string path = testing::TempDir() + "/surface_round_trip.exr";
  writeSurfaceImage(path, s);
  SurfaceImage r = readSurfaceImage(path);
  ASSERT_EQ(r.width, 7);
  ASSERT_EQ(r.height, 3);
  for (size_t i = 0; i < s.t.size(); ++i) {
    EXPECT_EQ(r.hit(i), s.hit(i)) << i;
    EXPECT_EQ(r.t[i], s.t[i]) << i;  // misses: +inf both
    EXPECT_EQ(r.normal[i], s.normal[i]) << i;
  }
  std::filesystem::remove(path);

  EXPECT_THROW(readSurfaceImage(testing::TempDir() + "/no_such_surface.exr"), InputError);
  EXPECT_THROW(writeSurfaceImage(testing::TempDir() + "/surface.png", s), InputError);
  // A colour image is not a surface image.
  std::string colour = testing::TempDir() + "/colour.exr";
  writeImage(colour, ImageF(4, 4), glm::dvec3(0.0));
  EXPECT_THROW(readSurfaceImage(colour), InputError);
  std::filesystem::remove(colour);
}

TEST(SurfaceReferenceJob, WritesTheShadedFrameAndTheSurface) {
  if (!build::kExr) GTEST_SKIP() << "this build has no OpenEXR (SORTLAST_WITH_EXR)";
  SurfaceReferenceJob job;
  job.positions = {{0.0, 0.0, 0.0}, {0.2, 0.0, 0.0}};
  job.h = kH;
  job.threshold = kT;
  job.colour = {0.6, 1.0, 0.2};
  job.camera = cameraAt({0.1, 0.3, 1.5}, {0.1, 0.0, 0.0}, 40, 30, 30.0);
  job.clip = bigBox();
  job.output = testing::TempDir() + "/surface_job.png";
  job.surface_out = testing::TempDir() + "/surface_job.exr";
  job.threads = 2;
  ASSERT_EQ(runSurfaceReference(job), 0);
  SurfaceImage want = referenceSurface({job.positions, kH, kT}, job.camera, job.clip, 1);
  SurfaceImage got = readSurfaceImage(job.surface_out);
  EXPECT_EQ(got.t, want.t);
  EXPECT_EQ(got.normal, want.normal);
  ImageRGBA8 frame = readImageRGBA8(job.output);  // opaque PNG over the black background
  ImageRGBA8 shaded = shadeSurface(want, job.camera, job.colour);
  for (size_t i = 0; i < frame.px.size(); i += 4)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(frame.px[i + c], shaded.px[i + c]) << i / 4;
  std::filesystem::remove(job.output);
  std::filesystem::remove(job.surface_out);

  job.h = -1.0;  // bad input: an error message and exit code 1, no exception
  EXPECT_EQ(runSurfaceReference(job), 1);
}

TEST(ReferenceWithSurface, StopsTheIntegralAndShowsTheSurface) {
  // A 9^3 volume with a gradient through it; a transfer function with some opacity everywhere.
  WholeVolume vol;
  vol.grid.dims = glm::ivec3(9);
  vol.grid.spacing = glm::dvec3(0.25);
  for (int z = 0; z < 9; ++z)
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 9; ++x) vol.samples.push_back(float(x + y + z));
  TransferFunction tf({{0.0, 1.0, 0.0, 0.0, 0.2}, {1.0, 0.0, 0.0, 1.0, 0.6}}, 0.0, 24.0, 0.25);
  Camera cam = cameraAt({0.3, 0.4, 4.0}, {0.0, 0.0, 0.0}, 16, 12, 40.0);
  const double step = 0.25 / 16;
  ImageF plain = renderReference(vol, tf, cam, step, 2);

  // No surface anywhere: bit-identical to the volume-only reference.
  SurfaceImage none(16, 12);
  ImageF zero(16, 12);
  ImageF same = renderReference(vol, tf, cam, step, 2, none, zero);
  EXPECT_EQ(same.px, plain.px);

  // A surface in front of the volume everywhere: only the surface. One inside it: between.
  SurfaceImage front(16, 12), middle(16, 12);
  ImageF colour(16, 12);
  for (size_t i = 0; i < front.t.size(); ++i) {
    front.t[i] = 1.0f;
    middle.t[i] = 4.0f;
    colour.px[4 * i + 1] = 0.5f;
    colour.px[4 * i + 3] = 1.0f;
  }
  ImageF f = renderReference(vol, tf, cam, step, 2, front, colour);
  EXPECT_EQ(f.px, colour.px);
  ImageF m = renderReference(vol, tf, cam, step, 2, middle, colour);
  for (size_t i = 0; i < front.t.size(); ++i) {
    EXPECT_FLOAT_EQ(m.px[4 * i + 3], 1.0f);
    // Less volume in front than the full integral, and the surface's green shows through.
    EXPECT_LT(m.px[4 * i + 0], plain.px[4 * i + 0] + 1e-7f);
    EXPECT_GT(m.px[4 * i + 1], 0.0f);
  }
  EXPECT_THROW(renderReference(vol, tf, cam, step, 2, SurfaceImage(3, 3), zero), InputError);
}

}  // namespace
}  // namespace sortlast
