// The CPU side of bench/subdivision/run: for each mesh, the paper's precomputation time
// (control mesh, eigenbases, 45 x 16 points per irregular patch), evaluation rates, the error
// figures of the tests (exact evaluation against OpenSubdiv, float tables against exact) and the
// coarse meshes' deviation from the limit surface. One CSV row per mesh on stdout.
//
// Usage: subdiv_bench MESH[@R] ...   MESH: a procedural name (subdiv/subdiv_input.h) or an .obj
//        file; @R refines it R times first (Catmull-Clark, then a small irregular deformation) to
//        reach a face count.
#include <glm/geometric.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "common/error.h"
#include "subdiv/subdiv_coarse.h"
#include "subdiv/subdiv_input.h"
#include "subdiv/subdiv_tables.h"
#include "subdiv_reference.h"

using namespace sortlast;

namespace {

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

double degreesBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 180 / std::numbers::pi;
}

PolyMesh load(const std::string& spec) {
  const size_t at = spec.find('@');
  const std::string name = spec.substr(0, at);
  PolyMesh m = name.size() > 4 && name.substr(name.size() - 4) == ".obj" ? readObjMesh(name) : proceduralMesh(name);
  const int refine = at == std::string::npos ? 0 : std::stoi(spec.substr(at + 1));
  for (int r = 0; r < refine; ++r) {
    RefinedMesh next = catmullClarkStep(m, checkMesh(m));
    const double size = next.mesh.size();
    for (size_t i = 0; i < next.mesh.points.size(); ++i)
      next.mesh.points[i] += 0.01 * size * glm::dvec3(std::sin(1.3 * i), std::cos(0.7 * i + 1), std::sin(2.1 * i + 2));
    m = std::move(next.mesh);
  }
  m.name = spec;
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  std::printf("mesh,input_faces,control_faces,irregular_patches,valences,precompute_ms,precompute_ms_per_1000_faces,"
              "exact_evals_per_s,table_evals_per_s,osd_position_error,osd_normal_error_deg,"
              "table_position_error,table_normal_error_deg,coarse_deviation_l1,coarse_deviation_l2,coarse_deviation_l3\n");
  try {
    for (int a = 1; a < argc; ++a) {
      const PolyMesh input = load(argv[a]);
      auto start = std::chrono::steady_clock::now();
      const SubdivSurface surface(input);
      const SubdivTables tables = buildTables(surface);
      const double precompute = seconds(start);
      int irregular = 0;
      for (int f = 0; f < surface.patchCount(); ++f) irregular += !surface.regular(f);
      std::string valences;
      for (const auto& [n, basis] : surface.bases()) valences += (valences.empty() ? "" : " ") + std::to_string(n);

      // Sample points: a 4 x 4 grid per control face plus a run towards each corner (to 2^-8).
      std::vector<std::pair<double, double>> uv;
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) uv.emplace_back((i + 0.5) / 4, (j + 0.5) / 4);
      for (int level = 2; level <= 8; ++level)
        for (int c = 0; c < 4; ++c) {
          const double d = std::ldexp(0.8, -level);
          uv.emplace_back(c & 1 ? 1 - d : d, c & 2 ? 1 - 0.6 * d : 0.6 * d);
        }
      OsdReference reference(input, 10);
      double osdPosition = 0, osdNormal = 0, tablePosition = 0, tableNormal = 0;
      for (int f = 0; f < surface.patchCount(); ++f)
        for (const auto& [u, v] : uv) {
          const LimitPoint ours = surface.evaluate(f, u, v), theirs = reference.evaluate(surface.control(), f, u, v);
          osdPosition = std::max(osdPosition, glm::length(ours.position - theirs.position));
          osdNormal = std::max(osdNormal, degreesBetween(ours.normal, theirs.normal));
          const FloatLimitPoint t = evaluateTables(tables, f, float(u), float(v));
          const LimitPoint there = surface.evaluate(f, double(float(u)), double(float(v)));
          tablePosition = std::max(tablePosition, glm::length(glm::dvec3(t.position) - there.position));
          tableNormal = std::max(tableNormal, degreesBetween(glm::dvec3(t.normal), there.normal));
        }
      // Evaluation rates on one core: what a CPU would pay per fragment.
      const long evaluations = 200000;
      double sink = 0;
      start = std::chrono::steady_clock::now();
      for (long i = 0; i < evaluations; ++i)
        sink += surface.evaluate(int(i % surface.patchCount()), uv[i % uv.size()].first, uv[i % uv.size()].second).position.x;
      const double exactRate = evaluations / seconds(start);
      start = std::chrono::steady_clock::now();
      for (long i = 0; i < evaluations; ++i)
        sink += evaluateTables(tables, int(i % surface.patchCount()), float(uv[i % uv.size()].first),
                               float(uv[i % uv.size()].second)).position.x;
      const double tableRate = evaluations / seconds(start);
      const double size = input.size();
      std::string deviation;
      for (int level = 1; level <= 3; ++level)
        deviation += "," + (level < surface.control().levels ? std::string("") : std::to_string(coarseDeviation(surface, level)));
      std::printf("%s,%d,%d,%d,%s,%.3f,%.3f,%.0f,%.0f,%.3g,%.3g,%.3g,%.3g%s\n", input.name.c_str(), input.faceCount(),
                  surface.patchCount(), irregular, valences.c_str(), precompute * 1e3,
                  precompute * 1e6 / input.faceCount(), exactRate, tableRate, osdPosition / size, osdNormal,
                  tablePosition / size, tableNormal, deviation.c_str());
      std::fflush(stdout);
      if (sink == 12345.678) std::fprintf(stderr, " ");  // keeps the timed loops from being dropped
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
