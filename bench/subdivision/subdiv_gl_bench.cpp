// The GL side of bench/subdivision/run: frames per second of render/surfaces/subdiv_renderer for a
// mesh at an image size, over an orbit of F frames (frame 0, the warm-up, left out), with the
// seconds for setSurface (tables, coarse mesh, upload), the seconds of the draw alone (to
// glFinish; the rest of a frame is the read-back) and the fragment shader invocations of one frame
// per covered pixel (llvmpipe counts whole 4 x 4 blocks: the overdraw the blocks on small
// triangles' edges cause; it counts pass 2's blocks that the stencil test skips too). One CSV row
// on stdout.
//
// Usage: subdiv_gl_bench MESH[@R] SIZE LEVEL FRAMES MODE NEWTON [BACKEND]   (MESH as subdiv_bench: a
// procedural name or an .obj file)
#include <glm/geometric.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "common/error.h"
#include "subdiv/subdiv_input.h"
#include "render/surfaces/subdiv_renderer.h"

using namespace sortlast;

int main(int argc, char** argv) {
  if (argc < 7) {
    std::fprintf(stderr, "usage: subdiv_gl_bench MESH[@R] SIZE LEVEL FRAMES MODE NEWTON [BACKEND]\n");
    return 2;
  }
  try {
    const std::string spec = argv[1];
    const size_t at = spec.find('@');
    const std::string name = spec.substr(0, at);
    PolyMesh m = name.size() > 4 && name.substr(name.size() - 4) == ".obj" ? readObjMesh(name) : proceduralMesh(name);
    for (int r = 0; r < (at == std::string::npos ? 0 : std::stoi(spec.substr(at + 1))); ++r) {
      RefinedMesh next = catmullClarkStep(m, checkMesh(m));
      const double size = next.mesh.size();
      for (size_t i = 0; i < next.mesh.points.size(); ++i)
        next.mesh.points[i] += 0.01 * size * glm::dvec3(std::sin(1.3 * i), std::cos(0.7 * i + 1), std::sin(2.1 * i + 2));
      m = std::move(next.mesh);
    }
    const int size = std::stoi(argv[2]), level = std::stoi(argv[3]), frames = std::stoi(argv[4]);
    SubdivShading shading;
    shading.mode = argv[5];
    shading.newton_steps = std::stoi(argv[6]);
    auto ctx = createGlContext(argc > 7 ? argv[7] : "osmesa");
    SubdivRenderer renderer(*ctx, size, size);
    const SubdivSurface surface(m);
    auto start = std::chrono::steady_clock::now();
    renderer.setSurface(surface, std::max(level, surface.control().levels), shading);
    const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : m.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    Camera cam;
    cam.look_at = 0.5 * (lo + hi);
    cam.width = cam.height = size;
    const double radius = 1.6 * m.size();
    const Box3 all{glm::dvec3(-1e30), glm::dvec3(1e30)};
    double total = 0, draw_total = 0;
    // Fragment shader invocations of frame 1 over the pixels covered: the overdraw.
    const GlApi& gl = ctx->gl();
    unsigned query = 0;
    gl.GenQueries(1, &query);
    long covered = 0;
    for (int f = 0; f < frames; ++f) {
      const double a = 2 * std::numbers::pi * f / frames;
      cam.position = cam.look_at + radius * glm::dvec3(std::cos(a), 0.4, std::sin(a));
      start = std::chrono::steady_clock::now();
      if (f == 1) gl.BeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS, query);
      renderer.draw(cam, all, 0.05 * radius, 3 * radius);
      if (f == 1) gl.EndQuery(GL_FRAGMENT_SHADER_INVOCATIONS);
      gl.Finish();
      const auto drawn = std::chrono::steady_clock::now();
      SubdivFrame frame;
      renderer.read({0, 0, size, size}, &frame.pixels, &frame.surface);
      const auto end = std::chrono::steady_clock::now();
      if (f > 0) {
        total += std::chrono::duration<double>(end - start).count();
        draw_total += std::chrono::duration<double>(drawn - start).count();
      }
      if (f == 0)
        for (size_t i = 3; i < frame.pixels.px.size(); i += 4) covered += frame.pixels.px[i] != 0;
    }
    unsigned invocations = 0;
    if (frames > 1) gl.GetQueryObjectuiv(query, GL_QUERY_RESULT, &invocations);
    std::printf("%s,%d,%d,%d,%s,%d,%d,%.4f,%.4f,%.2f,%ld,%.4f,%.3f\n", spec.c_str(), m.faceCount(), surface.patchCount(), size,
                shading.mode.c_str(), shading.newton_steps, std::max(level, surface.control().levels), setup,
                total / (frames - 1), (frames - 1) / total, covered,
                draw_total / (frames - 1), covered ? double(invocations) / covered : 0.0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
