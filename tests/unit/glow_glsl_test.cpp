// The GLSL of the glow integral (render/glow/glow_segment.glsl) run on the GL driver (OSMesa:
// llvmpipe), one ray per pixel, against the double closed form (glow/glow_integral.h) on the same
// float inputs: the float bound the C++ float instantiation meets (tests/unit/glow_test.cpp, 2e-5)
// must hold for the shader too. Its own executable: it needs a GL context, which the unit tests
// never make.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "glow/glow_integral.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"
#include "render/gl/glsl_files.h"  // generated from render/gl/*.glsl (cmake/embed_shaders.cmake)
#include "render/glow/glow_gl.h"
#include "render/glow/glsl_files.h"
#include "tests/unit/glsl/glsl_files.h"

namespace sortlast {
namespace {

struct Ray {
  glm::vec3 centre, dir, o, u;
  float a, b, eps, s0, s1;
};

double closed(const Ray& r) {
  return glowSegment<double>(glm::dvec3(r.centre), glm::dvec3(r.dir), r.a, r.b, r.eps,
                             glm::dvec3(r.o), glm::dvec3(r.u), r.s0, r.s1);
}

// Moving M by 4 float ulps of the ray's scale changes the integral by more than a quarter of the
// bound: no float evaluation can pin it down (the same test as glow_test.cpp's).
bool illConditioned(const Ray& r, double bound) {
  const double scale = glm::length(glm::dvec3(r.o - r.centre)) + std::abs(r.s0) + std::abs(r.s1);
  const double nudge = 4.0 * std::ldexp(scale, -24), base = closed(r);
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      glm::dvec3 c(r.centre);
      c[axis] += sign * nudge;
      double v = glowSegment<double>(c, glm::dvec3(r.dir), r.a, r.b, r.eps, glm::dvec3(r.o),
                                     glm::dvec3(r.u), r.s0, r.s1);
      if (std::abs(v - base) > 0.25 * bound * base) return true;
    }
  return false;
}

std::vector<Ray> rays() {
  std::mt19937 g(1616);
  std::uniform_real_distribution<float> c(-1.0f, 1.0f), uni(0.0f, 1.0f);
  std::normal_distribution<float> n;
  auto unit = [&] {
    glm::vec3 v;
    do v = {n(g), n(g), n(g)};
    while (glm::length(v) < 1e-3f);
    return glm::normalize(v);
  };
  auto logU = [&](float lo, float hi) {
    return std::exp(std::log(lo) + uni(g) * (std::log(hi) - std::log(lo)));
  };
  std::vector<Ray> out;
  for (int i = 0; i < 2048; ++i) {
    Ray r;
    r.centre = {c(g), c(g), c(g)};
    r.dir = unit();
    r.a = 0.1f + uni(g);
    r.b = 0.1f + uni(g);
    r.eps = logU(1e-4f, 1.0f);
    r.s0 = 0.0f;
    switch (i % 4) {
      case 0:  // anywhere
        r.o = r.centre + 3.0f * glm::vec3(c(g), c(g), c(g));
        r.u = unit();
        r.s1 = logU(1e-3f, 20.0f);
        break;
      case 1: {  // through M, or nearly
        r.u = unit();
        r.o = r.centre - 2.0f * r.u;
        r.s0 = 2.0f * uni(g);
        r.s1 = r.s0 + logU(1e-4f, 1e3f);
        break;
      }
      case 2: {  // nearly parallel to the axis, 0 .. 1e-2 rad
        glm::vec3 side = glm::normalize(glm::cross(r.dir, unit()));
        float angle = i % 8 == 2 ? 0.0f : logU(1e-7f, 1e-2f);
        r.u = glm::normalize(r.dir * std::cos(angle) + side * std::sin(angle));
        r.o = r.centre + logU(1e-3f, 10.0f) * glm::normalize(glm::cross(r.dir, side)) +
              (c(g) * 5.0f) * r.dir;
        r.s1 = logU(1e-3f, 1e3f);
        break;
      }
      default: {  // along the plane, a = b
        r.u = glm::normalize(glm::cross(r.dir, unit()));
        r.b = r.a;
        r.o = r.centre - 3.0f * r.u + logU(1e-3f, 2.0f) * glm::normalize(glm::cross(r.dir, r.u));
        r.s1 = logU(1e-3f, 1e2f);
        break;
      }
    }
    out.push_back(r);
  }
  return out;
}

TEST(GlowGlsl, ShaderMatchesTheClosedForm) {
  std::unique_ptr<GlContext> ctx;
  try {
    ctx = createGlContext("osmesa");
  } catch (const std::exception& e) {
    GTEST_FAIL() << "no GL context: " << e.what();
  }
  const GlApi& gl = ctx->gl();
  const std::vector<Ray> cases = rays();
  const int n = int(cases.size());
  // Case i is row i of a 4-texel-wide RGBA32F texture: (centre, a), (dir, b), (o, eps), (u, s0),
  // and s1 in a fifth.
  std::vector<float> texels;
  for (const Ray& r : cases)
    for (float v :
         {r.centre.x, r.centre.y, r.centre.z, r.a,   r.dir.x, r.dir.y, r.dir.z, r.b,  r.o.x, r.o.y,
          r.o.z,      r.eps,      r.u.x,      r.u.y, r.u.z,   r.s0,    r.s1,    0.0f, 0.0f,  0.0f})
      texels.push_back(v);
  unsigned program =
      linkProgram(gl, ShaderSource().add(glsl::fullscreen_vert),
                  ShaderSource().add(glsl::glow_segment).add(glsl::glow_segment_test_frag));
  unsigned vao = 0;
  const unsigned target = makeFloatTexture(gl, n, 1, nullptr);
  const unsigned fbo = makeFramebuffer(gl, target);  // throws if incomplete
  const unsigned tex = makeFloatTexture(gl, 5, n, texels.data());  // bound to unit 0
  gl.UseProgram(program);
  gl.Uniform1i(gl.GetUniformLocation(program, "u_cases"), 0);
  gl.GenVertexArrays(1, &vao);
  gl.BindVertexArray(vao);
  gl.Viewport(0, 0, n, 1);
  gl.DrawArrays(GL_TRIANGLES, 0, 3);
  std::vector<float> out(size_t(n) * 4);
  gl.ReadPixels(0, 0, n, 1, GL_RGBA, GL_FLOAT, out.data());
  ASSERT_EQ(gl.GetError(), unsigned(GL_NO_ERROR));

  constexpr double kBound = 2e-5;  // glow_test.cpp's float bound
  double worst[4] = {0, 0, 0, 0};
  int skipped = 0;
  for (int i = 0; i < n; ++i) {
    const float v = out[4 * size_t(i)];
    ASSERT_TRUE(std::isfinite(v)) << "case " << i;
    if (illConditioned(cases[i], kBound)) {
      ++skipped;
      continue;
    }
    const double d = closed(cases[i]), rel = std::abs(v - d) / d;
    worst[i % 4] = std::max(worst[i % 4], rel);
    EXPECT_LE(rel, kBound) << "case " << i << ": GLSL " << v << " double " << d;
  }
  std::printf(
      "glow GLSL on %s: worst relative error anywhere %.2e, through M %.2e, parallel to the axis "
      "%.2e, along the plane %.2e (bound %.0e); %d of %d rays ill-conditioned in float (finite)\n",
      ctx->description().c_str(), worst[0], worst[1], worst[2], worst[3], kBound, skipped, n);
  gl.DeleteVertexArrays(1, &vao);
  gl.DeleteFramebuffers(1, &fbo);
  gl.DeleteTextures(1, &target);
  gl.DeleteTextures(1, &tex);
  gl.DeleteProgram(program);
}

}  // namespace
}  // namespace sortlast
