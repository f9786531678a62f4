// The glow emitters' GL cost alone: one fullscreen pass per frame evaluates every
// emitter's exact segment integral (render/glow/glow_segment.glsl) over each pixel's ray inside the
// glow box, on llvmpipe; then the frame's PSNR (8-bit, after the tone map) against the same
// integral in double on the CPU. What one brick's glow pass (render/glow/glow_renderer.h) costs
// with d = 1, without the pipeline around it (bench/glow/run measures that too, through
// `sortlast render`).
//
// Usage: bench_glow EMITTERS SIZE FRAMES   -> one CSV line:
// emitters,size,frames,ms_per_frame,fps,psnr_db
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "bench/glow/glsl_files.h"  // generated from bench/glow/*.glsl (cmake/embed_shaders.cmake)
#include "common/camera.h"
#include "glow/glow_integral.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"
#include "render/gl/glsl_files.h"
#include "render/glow/glow_gl.h"
#include "render/glow/glsl_files.h"

using namespace sortlast;

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: bench_glow EMITTERS SIZE FRAMES [osmesa|egl]\n");
    return 2;
  }
  const int count = std::atoi(argv[1]), size = std::atoi(argv[2]), frames = std::atoi(argv[3]);
  if (count < 1 || size < 1 || frames < 1) {
    std::fprintf(stderr, "bench_glow: EMITTERS, SIZE and FRAMES must be >= 1\n");
    return 2;
  }
  const float eps = 0.02f, intensity = 0.6f / std::sqrt(float(count)), exposure = 1.0f;
  const glm::vec3 lo(-2.0f), hi(2.0f);
  std::mt19937 g(16);
  std::uniform_real_distribution<float> c(-1.5f, 1.5f), u(0.2f, 1.0f);
  std::normal_distribution<float> n;
  // Float values (the shader's) held in double: the reference integrates the same emitters.
  std::vector<GlowEmitter> em;
  for (int i = 0; i < count; ++i) {
    GlowEmitter e;
    e.centre = glm::vec3(c(g), c(g), c(g));
    e.direction = glm::normalize(glm::vec3(n(g), n(g), n(g)));
    e.colour = glm::vec3(u(g), u(g), u(g));
    e.a = u(g);
    e.b = u(g);
    em.push_back(e);
  }
  const std::vector<float> texels = glowEmitterTexels(em);
  Camera cam;
  cam.position = {1.0, 2.0, 7.0};
  cam.look_at = {0.0, 0.0, 0.0};
  cam.width = cam.height = size;

  auto ctx = createGlContext(argc > 4 ? argv[4] : "osmesa");  // egl: scripts/gpu-check
  const GlApi& gl = ctx->gl();
  // The glow pass's chunks (render/glow/glow_renderer.cpp) with this benchmark's main.
  const GlProgram program(gl, linkProgram(gl, ShaderSource().add(glsl::fullscreen_vert),
                                          ShaderSource()
                                              .add(glsl::glow_segment)
                                              .add(glsl::glow_emitters)
                                              .add(glsl::glow_along)
                                              .add(glsl::glow_pixel_ray)
                                              .add(glsl::bench_glow_frag)));
  unsigned vao = 0;
  const unsigned target = makeFloatTexture(gl, size, size, nullptr);
  makeFramebuffer(gl, target);
  const unsigned emitters = makeFloatTexture(gl, 3, count, texels.data());
  gl.UseProgram(program);
  bindGlowEmitters(gl, program, GlowPass{emitters, count, eps, intensity, {}, {}}, 0);
  setPixelRayUniforms(program, cam);
  program.set("u_box_lo", lo);
  program.set("u_box_hi", hi);
  program.set("u_intensity", intensity);
  program.set("u_exposure", exposure);
  gl.GenVertexArrays(1, &vao);
  gl.BindVertexArray(vao);
  gl.Viewport(0, 0, size, size);
  std::vector<float> px(size_t(size) * size * 4);
  // One untimed frame (shader compile on first draw), then the timed ones: draw and read back.
  std::vector<double> ms;
  for (int f = 0; f <= frames; ++f) {
    auto t = std::chrono::steady_clock::now();
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.ReadPixels(0, 0, size, size, GL_RGBA, GL_FLOAT, px.data());
    double dt =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
    if (f > 0) ms.push_back(dt);
  }
  std::sort(ms.begin(), ms.end());
  const double median = ms[ms.size() / 2];
  // PSNR against the double integral, both tone-mapped and rounded to 8 bits. Row y of the
  // target is image row y from the top (as the ray caster's: s.y = 1 - 2 (y + 0.5) / height).
  double se = 0.0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      glm::dvec3 o = cam.position, d = cam.rayDirection(x, y), sum(0.0);
      double t0, t1;
      if (intersectRayBox(o, d, Box3{glm::dvec3(lo), glm::dvec3(hi)}, t0, t1) &&
          t1 > std::max(t0, 0.0))
        for (const GlowEmitter& e : em)
          sum += e.colour * glowSegment<double>(e.centre, e.direction, e.a, e.b, eps, o, d,
                                                std::max(t0, 0.0), t1);
      for (int k = 0; k < 3; ++k) {
        double ref = std::round(255.0 * -std::expm1(-double(exposure) * intensity * sum[k]));
        double got =
            std::round(255.0 * std::clamp(double(px[4 * (size_t(y) * size + x) + k]), 0.0, 1.0));
        se += (ref - got) * (ref - got);
      }
    }
  const double mse = se / (3.0 * size * size);
  const double psnr = mse > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : INFINITY;
  std::printf("%d,%d,%d,%.3f,%.2f,%.2f\n", count, size, frames, median, 1000.0 / median, psnr);
  return 0;
}
