// A synthetic "simulation" for the in-situ tests: an analytic field on an N^3 grid cut into blocks
// the way a simulation might (slabs, 2x2x1, an uneven split, a rank with no cells, MPI_Dims_create),
// published with or without ghost layers, as float32, float64 or uint8, and/or particles spread
// over the ranks. Rank 0 also writes the whole field (or the particles, in rank order) to a raw
// file, so the test can render the same data with `sortlast render` and compare.
//
//   insitu_driver --size N --split slabs|2x2x1|uneven|empty|cart [--ghosts] [--type f32|f64|u8]
//                 [--particles K] [--no-grid] --steps S --actions FILE --dump FILE
//                 [--nan-step S] [--step-ms MS]
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "sortlast/insitu.h"

namespace {

struct Options {
  int size = 32, steps = 1, particles = 0, nan_step = -1, step_ms = 0;
  std::string split = "slabs", type = "f32", actions, dump;
  bool ghosts = false, no_grid = false;
};

double field(int i, int j, int k, int n) {
  // Two soft blobs and a ripple: smooth, with structure everywhere.
  double x = (i + 0.5) / n - 0.5, y = (j + 0.5) / n - 0.5, z = (k + 0.5) / n - 0.5;
  double a = std::exp(-((x - 0.15) * (x - 0.15) + y * y + z * z) / 0.02);
  double b = std::exp(-((x + 0.2) * (x + 0.2) + (y - 0.1) * (y - 0.1) + (z + 0.1) * (z + 0.1)) / 0.01);
  return 0.7 * a + 0.9 * b + 0.1 * (1 + std::sin(12 * x + 7 * y)) * (1 - 4 * z * z);
}

// This rank's owned samples [lo, hi) per axis.
void blockOf(const Options& o, int rank, int ranks, int lo[3], int hi[3]) {
  const int n = o.size;
  for (int a = 0; a < 3; ++a) lo[a] = 0, hi[a] = n;
  auto cut = [&](int axis, int parts, int index, const std::vector<int>& bounds) {
    (void)parts;
    lo[axis] = bounds[size_t(index)], hi[axis] = bounds[size_t(index) + 1];
  };
  auto even = [&](int parts) {
    std::vector<int> b;
    for (int p = 0; p <= parts; ++p) b.push_back(int(1LL * n * p / parts));
    return b;
  };
  if (o.split == "slabs") {
    cut(2, ranks, rank, even(ranks));
  } else if (o.split == "2x2x1") {  // needs 4 ranks
    cut(0, 2, rank % 2, even(2));
    cut(1, 2, rank / 2, even(2));
  } else if (o.split == "uneven") {  // slabs along x of very different widths
    std::vector<int> b{0};
    for (int p = 1; p < ranks; ++p) b.push_back(n * p * p / (ranks * ranks) + (p == 1 ? 2 : 0));
    b.push_back(n);
    cut(0, ranks, rank, b);
  } else if (o.split == "empty") {  // the last rank owns nothing
    if (rank == ranks - 1) {
      lo[0] = hi[0] = 0;
    } else {
      cut(1, ranks - 1, rank, even(ranks - 1));
    }
  } else if (o.split == "cart") {
    int dims[3] = {0, 0, 0};
    MPI_Dims_create(ranks, 3, dims);
    int c[3] = {rank % dims[0], (rank / dims[0]) % dims[1], rank / (dims[0] * dims[1])};
    for (int a = 0; a < 3; ++a) cut(a, dims[a], c[a], [&] {
        std::vector<int> b;
        for (int p = 0; p <= dims[a]; ++p) b.push_back(int(1LL * n * p / dims[a]));
        return b;
      }());
  } else {
    std::fprintf(stderr, "unknown split %s\n", o.split.c_str());
    std::exit(2);
  }
}

template <class T>
std::vector<T> fill(const Options& o, const int lo[3], const int hi[3], int g, int step, bool nan, double scale) {
  const int nx = hi[0] - lo[0] + 2 * g, ny = hi[1] - lo[1] + 2 * g, nz = hi[2] - lo[2] + 2 * g;
  std::vector<T> v(size_t(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        int gi = std::clamp(lo[0] + i - g, 0, o.size - 1), gj = std::clamp(lo[1] + j - g, 0, o.size - 1),
            gk = std::clamp(lo[2] + k - g, 0, o.size - 1);
        double f = field(gi, gj, gk, o.size) * (1.0 + 0.05 * step);
        v[(size_t(k) * ny + j) * nx + i] = T(f * scale);
      }
  if (nan && !v.empty()) v[v.size() / 2] = T(NAN);
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&] { return std::string(i + 1 < argc ? argv[++i] : ""); };
    if (a == "--size") o.size = std::atoi(next().c_str());
    else if (a == "--split") o.split = next();
    else if (a == "--ghosts") o.ghosts = true;
    else if (a == "--type") o.type = next();
    else if (a == "--particles") o.particles = std::atoi(next().c_str());
    else if (a == "--no-grid") o.no_grid = true;
    else if (a == "--steps") o.steps = std::atoi(next().c_str());
    else if (a == "--actions") o.actions = next();
    else if (a == "--dump") o.dump = next();
    else if (a == "--nan-step") o.nan_step = std::atoi(next().c_str());
    else if (a == "--step-ms") o.step_ms = std::atoi(next().c_str());
    else { std::fprintf(stderr, "unknown option %s\n", a.c_str()); MPI_Abort(MPI_COMM_WORLD, 2); }
  }
  // A communicator of our own, as a simulation would pass.
  MPI_Comm sim;
  MPI_Comm_dup(MPI_COMM_WORLD, &sim);
  int code = 0;
  try {
    sortlast::InSitu vis(sim, o.actions);
    int lo[3], hi[3];
    blockOf(o, rank, ranks, lo, hi);
    const bool empty = hi[0] <= lo[0] || hi[1] <= lo[1] || hi[2] <= lo[2];
    const int g = o.ghosts ? 1 : 0;
    const double scale = o.type == "u8" ? 120.0 : 1.0;
    // Particles: rank r holds every particle whose index % ranks == r (the set itself is fixed).
    std::vector<double> px, py, pz;
    for (int p = rank; p < o.particles; p += ranks) {
      double t = p * 0.61803398875;
      px.push_back(0.4 * std::sin(t * 2.1) + 0.05 * std::cos(t * 13.0));
      py.push_back(0.3 * std::cos(t * 1.3));
      pz.push_back(0.35 * std::sin(t * 0.7 + 1.0));
    }
    for (int step = 0; step < o.steps; ++step) {
      const bool nan = step == o.nan_step && rank == std::min(1, ranks - 1);
      std::vector<float> f32;
      std::vector<double> f64;
      std::vector<uint8_t> u8;
      sortlast::Published data;
      if (!o.no_grid && !empty) {
        sortlast::GridBlock& b = data.grid;
        if (o.type == "f64") f64 = fill<double>(o, lo, hi, g, step, nan, scale), b.data = f64.data(), b.type = sortlast::ElementType::kFloat64;
        else if (o.type == "u8") u8 = fill<uint8_t>(o, lo, hi, g, step, false, scale), b.data = u8.data(), b.type = sortlast::ElementType::kUint8;
        else f32 = fill<float>(o, lo, hi, g, step, nan, scale), b.data = f32.data(), b.type = sortlast::ElementType::kFloat32;
        for (int a = 0; a < 3; ++a) {
          b.dims[a] = hi[a] - lo[a] + 2 * g;
          // Ghost layers only where the grid goes on (a simulation has none beyond the boundary
          // here; the array still has room for them, which the strides skip).
          b.ghost_lo[a] = g;
          b.ghost_hi[a] = g;
          b.origin[a] = 10.0 + lo[a] * 0.5;  // the simulation's own coordinates
          b.spacing[a] = 0.5;
        }
      }
      if (!px.empty()) {
        data.particles.x = px.data(), data.particles.y = py.data(), data.particles.z = pz.data();
        data.particles.count = (long long)px.size();
      }
      data.quantities["step"] = step;
      if (o.step_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(o.step_ms));  // "simulating"
      vis.publish(step, 0.1 * step, data);
      sortlast::ExecuteReport r = vis.execute();
      if (rank == 0)
        std::printf("step %d rendered %d images %zu error '%s' vis_s %.3f mem_mib %.3f texture_mib %.3f "
                    "est_db %.3f lo %.3f hi %.3f over4 %.6f over4_hi %.6f why '%s'\n", step,
                    int(r.rendered), r.images.size(), r.error.c_str(), r.seconds, r.memory_added_mib, r.texture_mib,
                    r.estimated_psnr_db, r.psnr_db_lo, r.psnr_db_hi, r.over4_share, r.over4_share_hi,
                    r.accuracy_why.c_str());
      if (rank == 0 && !o.dump.empty() && step == o.steps - 1) {
        std::ofstream out(o.dump, std::ios::binary);
        if (!o.no_grid) {
          for (int k = 0; k < o.size; ++k)
            for (int j = 0; j < o.size; ++j)
              for (int i = 0; i < o.size; ++i) {
                double f = field(i, j, k, o.size) * (1.0 + 0.05 * step) * scale;
                float v = o.type == "u8" ? float(uint8_t(f)) : o.type == "f64" ? float(double(f)) : float(f);
                out.write(reinterpret_cast<const char*>(&v), 4);
              }
        } else {
          // Particles in rank order, then local order: what the ranks published, concatenated.
          for (int r = 0; r < ranks; ++r)
            for (int p = r; p < o.particles; p += ranks) {
              double t = p * 0.61803398875;
              float xyz[3] = {float(0.4 * std::sin(t * 2.1) + 0.05 * std::cos(t * 13.0)), float(0.3 * std::cos(t * 1.3)),
                              float(0.35 * std::sin(t * 0.7 + 1.0))};
              out.write(reinterpret_cast<const char*>(xyz), 12);
            }
        }
      }
    }
  } catch (const sortlast::InSituError& e) {
    if (rank == 0) std::printf("InSituError: %s\n", e.what());
    code = 3;
  }
  MPI_Comm_free(&sim);
  MPI_Finalize();
  return code;
}
