#include "session/adaptive_loading.h"
#include "session/device_report.h"  // nodePlace

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "common/error.h"
#include "io/volume_source.h"
#include "session/collective.h"

namespace sortlast {

bool usesAdaptiveBlocks(const Scene& scene) {
  if (!scene.hasVolume() || scene.adaptive.tolerance <= 0.0) return false;
  if (!scene.render.raycast())
    throw InputError("adaptive.tolerance > 0 needs render.method: raycast (3D-texture slicing "
                     "does not draw adaptive blocks); got render.method: " + std::string(nameOf(scene.render.method)));
  return true;
}

namespace {

// Cores for this rank's build: the node's, shared among the ranks on it (each builds the same
// volume at the same time).
int buildThreads(MPI_Comm comm) {
  const int on_node = nodePlace(comm).size;
  return std::max(1, int(std::max(1u, std::thread::hardware_concurrency())) / on_node);
}

double slowest(double mine, MPI_Comm comm) {
  double out = mine;
  MPI_Allreduce(&mine, &out, 1, MPI_DOUBLE, MPI_MAX, comm);
  return out;
}

}  // namespace

AdaptiveRankData loadAdaptiveBricks(const Scene& scene, const std::vector<Brick>& bricks,
                                    const std::vector<int>& mine, MPI_Comm comm) {
  AdaptiveRankData out;
  const int threads = buildThreads(comm);
  double read_s = 0, build_s = 0, bricks_s = 0;
  collectively(comm, [&] {
    double t0 = MPI_Wtime();
    const VolumeDesc& desc = scene.volume;
    std::vector<float> whole = readWholeVolume(desc);
    auto [lo, hi] = std::minmax_element(whole.begin(), whole.end());
    out.data_min = *lo, out.data_max = *hi;
    double t1 = MPI_Wtime();
    AdaptiveOptions options;
    options.blocks_per_axis = scene.adaptive.blocks;
    options.tolerance = scene.adaptive.tolerance;
    options.threads = threads;
    const AdaptiveVolume vol = buildAdaptive(desc.grid, whole, options);
    std::vector<float>().swap(whole);
    double t2 = MPI_Wtime();
    out.data_left = dataLeft(vol);
    // A thread per brick (up to `threads`): mostly copying into fresh memory, which first-touch
    // page faults make as slow as the build itself on one thread.
    out.bricks.resize(mine.size());
    std::atomic<size_t> next{0};
    std::exception_ptr failed;  // the first failure of any thread (e.g. out of memory)
    std::mutex failed_mutex;
    auto cut = [&] {
      try {
        for (size_t i; (i = next++) < mine.size();)
          out.bricks[i] = adaptiveBrickBlocks(vol, bricks[size_t(mine[i])].domain);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failed_mutex);
        if (!failed) failed = std::current_exception();
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < std::min(threads, int(mine.size())); ++t) pool.emplace_back(cut);
    cut();
    for (auto& t : pool) t.join();
    if (failed) std::rethrow_exception(failed);
    read_s = t1 - t0;
    build_s = t2 - t1;
    bricks_s = MPI_Wtime() - t2;
  });
  out.read_s = slowest(read_s, comm);
  out.preprocess_s = slowest(build_s, comm);
  out.bricks_s = slowest(bricks_s, comm);
  return out;
}

}  // namespace sortlast
