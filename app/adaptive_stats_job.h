#pragma once
// `sortlast adaptive-stats`: runs the adaptive-sampling preprocessing (adaptive/adaptive_blocks.h)
// on a scene's whole volume and prints, as one JSON object, what it keeps (data left, blocks per
// level, atlas size), what it costs (preprocessing seconds) and what it loses (error of the
// adaptive field at every original sample). One process; a measuring instrument.
#include <string>
#include <vector>

namespace sortlast {

struct AdaptiveStatsOptions {
  std::string scene;                   // empty: the built-in default scene
  std::vector<std::string> overrides;  // --set key.path=value
  int threads = 0;                     // <= 0: all cores
  int runs = 5;                        // preprocessing runs timed (the first one is cold)
};

// Returns the exit code: 0, or 1 after printing an InputError.
int runAdaptiveStatsJob(const AdaptiveStatsOptions& options);

}  // namespace sortlast
