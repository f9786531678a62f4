#include "app/adaptive_stats_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <nlohmann/json.hpp>
#include <thread>

#include "adaptive/adaptive_blocks.h"
#include "common/error.h"
#include "scene/file_steps.h"
#include "scene/scene.h"

namespace sortlast {

namespace {

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

nlohmann::ordered_json vec(const glm::ivec3& v) { return {v.x, v.y, v.z}; }

}  // namespace

int runAdaptiveStatsJob(const AdaptiveStatsOptions& options) {
  try {
    Scene scene = loadScene(options.scene, options.overrides);
    resolveFileSteps(scene);
    if (!scene.hasVolume()) throw InputError("adaptive-stats: the scene has no volume");
    if (options.runs < 1) throw InputError("adaptive-stats: --runs must be >= 1");
    const int threads = options.threads > 0
                            ? options.threads
                            : int(std::max(1u, std::thread::hardware_concurrency()));
    validateVolume(scene.volume);
    const GridGeometry& grid = scene.volume.grid;
    const std::vector<float> samples = readWholeVolume(scene.volume);

    AdaptiveOptions ao;
    ao.blocks_per_axis = scene.adaptive.blocks;
    ao.tolerance = scene.adaptive.tolerance;
    ao.threads = threads;
    // One builder for every run, as for the time steps of a series: the first run pays for fresh
    // memory, the later ones reuse it.
    AdaptiveBuilder builder;
    nlohmann::ordered_json runs = nlohmann::ordered_json::array(),
                           cpu = nlohmann::ordered_json::array();
    double best = std::numeric_limits<double>::infinity(), best_cpu = best;
    AdaptiveTimings best_phases;
    for (int r = 0; r < options.runs; ++r) {
      double c0 = processCpuSeconds();
      const AdaptiveVolume& v = builder.build(grid, samples, ao);
      double c = processCpuSeconds() - c0, t = v.timings.total();
      runs.push_back(t);
      cpu.push_back(c);
      if ((r > 0 || options.runs == 1) && t < best) best = t, best_cpu = c, best_phases = v.timings;
    }
    const AdaptiveVolume vol = builder.take();
    const AdaptiveSummary sum = summarise(vol, samples, threads);
    auto [lo, hi] = std::minmax_element(samples.begin(), samples.end());
    const double range = double(*hi) - double(*lo);

    nlohmann::ordered_json out;
    out["volume"] = {
        {"source",
         scene.volume.isProcedural() ? "procedural:" + scene.volume.procedural : scene.volume.file},
        {"dims", vec(grid.dims)},
        {"value_range", {*lo, *hi}}};
    out["tolerance_percent"] = 100.0 * ao.tolerance;
    out["blocks_requested"] = ao.blocks_per_axis;
    out["block_grid"] = vec(vol.blocks.blocks);
    out["block_cells"] = vec(vol.blocks.block_cells);
    out["max_level"] = vol.blocks.max_level;
    out["blocks_per_level"] = sum.blocks_per_level;
    out["data_left_percent"] = 100.0 * sum.data_left;
    out["atlas_stored_percent"] = 100.0 * sum.stored_fraction;
    out["atlas_dims"] = vec(vol.atlas_dims);
    out["atlas_bytes"] = vol.atlasTexels() * (long long)sizeof(float);
    out["threads"] = threads;
    out["preprocess_s_best"] = best;  // best of the warm runs (all runs if only one)
    out["preprocess_cpu_s_of_best"] = best_cpu;
    out["preprocess_s_cold"] = runs[0];
    out["preprocess_s_runs"] = runs;
    out["preprocess_cpu_s_runs"] = cpu;
    out["phases_s_of_best"] = {{"pyramid", best_phases.pyramid_s},
                               {"levels", best_phases.levels_s},
                               {"pack", best_phases.pack_s}};
    out["error_max"] = sum.max_error;
    out["error_rms"] = sum.rms_error;
    out["error_max_percent_of_range"] = range > 0 ? 100.0 * sum.max_error / range : 0.0;
    out["error_rms_percent_of_range"] = range > 0 ? 100.0 * sum.rms_error / range : 0.0;
    out["blocks_over_tolerance"] = sum.blocks_over_tolerance;
    // null where an all-zero block ends with some error (its relative error is infinite)
    out["worst_block_relative_error_percent"] =
        std::isfinite(sum.worst_block_relative_error)
            ? nlohmann::ordered_json(100.0 * sum.worst_block_relative_error)
            : nlohmann::ordered_json(nullptr);
    std::printf("%s\n", out.dump(2).c_str());
  } catch (const InputError& e) {
    std::fprintf(stderr, "sortlast: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace sortlast
