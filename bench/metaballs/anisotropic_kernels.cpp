// Times computeAnisotropicKernels (io/anisotropic_kernels.h) with the default parameters on a
// procedural set (h = 2 spacings, as configs/particles_layers.yaml): the grid renderer runs it
// once per brick and time step on the brick's particles and ghosts. One thread. Prints one JSON
// line: the fastest of `repeats` runs, seconds per million particles, and how many particles
// came out splash (s = 0), in between, and surface (s = 1).
// Usage: bench_anisotropic_kernels [procedural (splash | layers)] [count] [repeats]
//        bench_anisotropic_kernels FILE.raw h [repeats]   (float32 xyz, e.g. the dam break with
//                                                          h = 0.025 / (1 - 0.765625))
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "io/anisotropic_kernels.h"
#include "io/particles.h"

int main(int argc, char** argv) {
  using namespace sortlast;
  const std::string name = argc > 1 ? argv[1] : "splash";
  const bool file = name.size() > 4 && name.substr(name.size() - 4) == ".raw";
  long long count = argc > 2 && !file ? std::atoll(argv[2]) : 1000000;
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 3;
  const double spacing = 0.3;
  double h = 0.61;
  ParticleSet set;
  if (file) {
    ParticleDesc desc;
    desc.file = name;
    desc.format = "raw";
    set = loadParticles(desc);
    count = (long long)set.positions.size();
    h = argc > 2 ? std::atof(argv[2]) : 0.025 / (1.0 - 0.765625);
  } else {
    set = proceduralParticles(name, count, spacing);
  }
  double best = 1e30;
  long long splash = 0, between = 0, surface = 0;
  for (int i = 0; i < repeats; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    std::vector<ParticleKernel> k = computeAnisotropicKernels(set.positions, h, AnisotropicParams{});
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    splash = between = surface = 0;
    for (const ParticleKernel& p : k) (p.s <= 0.0f ? splash : p.s >= 1.0f ? surface : between)++;
  }
  std::printf("{\"set\": \"%s\", \"particles\": %lld, \"seconds\": %.4f, \"s_per_million\": %.4f, "
              "\"splash\": %lld, \"between\": %lld, \"surface\": %lld}\n",
              name.c_str(), count, best, best / (double(count) / 1e6), splash, between, surface);
}
