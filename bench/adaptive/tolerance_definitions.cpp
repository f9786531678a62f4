// One-off experiment behind the choice of what "tolerance x %" means (results/adaptive/README.md).
// The paper gives eq. 3 (a block's squared error) and tolerances in percent, but not what the
// percentage is of. For every block and level this computes eq. 3 exactly as the preprocessing does
// (it includes adaptive/adaptive_blocks.cpp to reach the per-level errors), then the data left under
// four readings of "E <= x %":
//   A: E <= x * sum v^2          B: E <= x^2 * n * R^2       (R: the value range, n: samples)
//   C: E <= x * n * R^2          D: E <= x^2 * sum v^2       (the one sortlast uses)
// Built with the project (target tolerance_definitions, bench/CMakeLists.txt); run from the
// repository root on a raw uint8 cube of N^3, optionally only z0 .. z0+nz-1:
//   build/bench/tolerance_definitions ../shared/data/inviwo_engine_256x256x256_uint8.raw 256 [z0 nz]
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "adaptive/adaptive_blocks.cpp"

using namespace sortlast;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s FILE.raw N [z0 nz]\n", argv[0]);
    return 2;
  }
  const int n = std::atoi(argv[2]);
  std::vector<unsigned char> raw(size_t(n) * n * n);
  std::ifstream(argv[1], std::ios::binary)
      .read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size()));
  const int z0 = argc > 3 ? std::atoi(argv[3]) : 0, nz = argc > 4 ? std::atoi(argv[4]) : n;
  std::vector<float> v(raw.begin() + size_t(z0) * n * n, raw.begin() + size_t(z0 + nz) * n * n);
  const glm::ivec3 dims{n, n, nz};
  auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  const double range = double(*hi) - double(*lo);
  std::printf("%s, samples z %d..%d; data left in %% of the original per tolerance\n", argv[1], z0,
              z0 + nz - 1);
  for (int b : {4, 8, 16}) {
    const BlockGrid g = makeBlockGrid(dims, b);
    std::vector<std::vector<float>> storage;
    const Pyramid pyr(v.data(), g.dims, g.blocks * g.block_cells, g.max_level, 2, storage);
    const std::vector<BlockMoments> moments = allMoments(v.data(), g, 2);
    std::vector<std::vector<double>> err(size_t(g.count()));
    std::vector<long long> count(size_t(g.count()));
    parallelFor(g.count(), 2, [&](int id) {
      const glm::ivec3 c = g.cellOf(id);
      count[id] = realSamplesOf(g, c).count();
      std::vector<double> ax, axy;
      for (int l = 1; l <= g.max_level; ++l)
        err[id].push_back(levelError(pyr, v.data(), g, c, l, INFINITY, ax, axy));
    });
    const char* names[] = {"A  x * sum v^2", "B  x^2 * n R^2", "C  x * n R^2", "D  x^2 * sum v^2"};
    for (int def = 0; def < 4; ++def) {
      std::printf("b=%-2d %-18s", b, names[def]);
      for (double pct : {0.0, 5.0, 10.0, 20.0, 40.0}) {
        const double x = pct / 100;
        double left = 0;
        for (int id = 0; id < g.count(); ++id) {
          const double s = moments[id].sum_sq, nr2 = double(count[id]) * range * range;
          const double budget = def == 0   ? x * s
                                : def == 1 ? x * x * nr2
                                : def == 2 ? x * nr2
                                           : x * x * s;
          int l = 0;
          while (l < g.max_level && err[id][l] <= budget) ++l;
          const glm::dvec3 m(g.block_cells >> l);
          left += m.x * m.y * m.z;
        }
        std::printf("  %2.0f%%: %6.2f", pct, 100 * left / (double(n) * n * nz));
      }
      std::printf("\n");
    }
  }
}
