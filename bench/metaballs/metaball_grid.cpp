// Times buildParticleGrid (render/particles/metaball_grid.h) the way the grid renderer calls it (cells of
// h/2 over the particles' box plus h), on a procedural set: it runs once per brick and time step,
// so in situ it is paid every step. Prints one JSON line; the fastest of --repeats runs.
// Usage: bench_metaball_grid [procedural (splash | layers)] [count] [repeats]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "io/particles.h"
#include "render/particles/metaball_grid.h"

int main(int argc, char** argv) {
  using namespace sortlast;
  const std::string name = argc > 1 ? argv[1] : "splash";
  const long long count = argc > 2 ? std::atoll(argv[2]) : 1000000;
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 3;
  const double spacing = 0.3, h = 0.61;  // configs/particles_layers.yaml
  ParticleSet set = proceduralParticles(name, count, spacing);
  Box3 b = set.bounds();
  Box3 bound{b.lo - h, b.hi + h};
  double best = 1e30;
  size_t items = 0, cells = 0;
  for (int i = 0; i < repeats; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    ParticleGrid g = buildParticleGrid(set.positions, bound, h, 0.5 * h);
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, s);
    items = g.items.size();
    cells = g.cellCount();
  }
  std::printf("{\"procedural\": \"%s\", \"particles\": %lld, \"cells\": %zu, \"items\": %zu, "
              "\"build_s\": %.4f, \"s_per_million\": %.4f}\n",
              name.c_str(), count, cells, items, best, best / (double(count) / 1e6));
  return 0;
}
