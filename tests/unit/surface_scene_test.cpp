// The `surfaces` scene key (scene/surface_scene.h): transforms, the mirroring case, defaults and
// the domain the layout frames; the CPU reference's own accuracy (reference/surface_reference.h).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

#include "common/error.h"
#include "subdiv/subdiv_eval.h"
#include "scene/surface_scene.h"
#include "reference/surface_reference.h"

namespace sortlast {
namespace {

std::vector<SurfaceSpec> parseSurfaceList(const std::string& yaml) { return parseSurfaces(YAML::Load(yaml), "."); }

// Outward normals: at the limit point of every control face's centre the normal points away from
// the surface's centre (pole5 is star-shaped about it).
double worstOutwardness(const PolyMesh& mesh) {
  SubdivSurface s(mesh);
  glm::dvec3 c(0.0);
  for (const auto& p : mesh.points) c += p;
  c /= double(mesh.points.size());
  double worst = 1.0;
  for (int f = 0; f < s.patchCount(); ++f) {
    const LimitPoint lp = s.evaluate(f, 0.5, 0.5);
    worst = std::min(worst, glm::dot(lp.normal, glm::normalize(lp.position - c)));
  }
  return worst;
}

TEST(SurfaceScene, TransformsAndMirroring) {
  auto s = parseSurfaceList("[{procedural: pole5, transform: {scale: 2, rotate: [0, 90, 0], translate: [10, 0, 0]}},"
                 " {procedural: pole5, transform: {scale: [-1, 1, 1]}},"
                 " {procedural: cube, transform: [[1, 0, 0, 5], [0, 2, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}]");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_NEAR(0.5 * (s[0].bounds.lo.x + s[0].bounds.hi.x), 10.0, 0.5);
  EXPECT_NEAR(s[2].bounds.lo.x, 4.0, 1e-12);
  EXPECT_NEAR(s[2].bounds.hi.y, 2.0, 1e-12);
  // A mirror turns faces inside out unless their corners are reversed.
  EXPECT_GT(worstOutwardness(*s[1].mesh), 0.2);
  EXPECT_GT(worstOutwardness(*s[0].mesh), 0.2);
  EXPECT_EQ(s[0].level, 2);
  EXPECT_EQ(s[0].shading.mode, "headlight");
  const Box3 d = surfacesDomain(s), b = surfacesBounds(s);
  EXPECT_LT(d.lo.x, b.lo.x);
  EXPECT_GT(d.hi.z, b.hi.z);
}

TEST(SurfaceScene, BadEntriesNameTheKey) {
  auto message = [](const std::string& yaml) {
    try {
      parseSurfaceList(yaml);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("{procedural: cube}").find("'surfaces': expected a list"), std::string::npos);
  EXPECT_NE(message("[{procedural: cube}, {procedural: cube, stripes: 0}]").find("surfaces[1].stripes"), std::string::npos);
  EXPECT_NE(message("[{procedural: cube, stripe_width: 1}]").find("surfaces[0].stripe_width"), std::string::npos);
  EXPECT_NE(message("[{procedural: cube, transform: [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]}]")
                .find("last row"),
            std::string::npos);
  EXPECT_NE(message("[{procedural: fan13}]").find("surfaces[0].procedural"), std::string::npos);
  EXPECT_NE(message("[{procedural: cube, transform: {translate: [1e300, 0, 0]}}]").find("surfaces[0].transform"),
            std::string::npos);
}

// The reference's limit points lie on their pixels' rays (Newton on the exact surface, crossing
// face edges): every hit is the exact evaluation at its own (face, u, v), so its error is its
// distance from the ray. Measured 8e-14 of the size.
TEST(SurfaceReference, LimitPointsLieOnTheirRays) {
  auto s = parseSurfaceList("[{procedural: pole5}]");
  SurfaceReference ref(s);
  Camera cam;
  cam.look_at = glm::dvec3(0.0);
  cam.position = glm::dvec3(1.6, 1.0, 2.6);
  cam.width = cam.height = 64;
  SurfaceImage img;
  ImageF colour;
  SurfaceReferenceStats st;
  ref.render(cam, 2, img, colour, &st);
  std::printf("  %lld hits, worst distance from the ray %.3g of the size, %lld stopped at a face edge\n", st.hits,
              st.worst_residual / s[0].mesh->size(), st.stopped_at_edge);
  EXPECT_GT(st.hits, 64 * 64 / 5);
  EXPECT_LT(st.worst_residual, 1e-9 * s[0].mesh->size());
  EXPECT_EQ(st.stopped_at_edge, 0);
}

}  // namespace
}  // namespace sortlast
