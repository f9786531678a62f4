#pragma once
// `sortlast render`: the frame loop on every rank.
#include <mpi.h>

#include "common/camera.h"

#include <string>
#include <vector>

namespace sortlast {

struct RenderOptions {
  std::string scene;                   // empty: built-in default scene
  std::vector<std::string> overrides;  // key.path=value
  std::string output = "sortlast.png";
  std::string stats;                   // JSON file, or empty
  std::string surface_out;             // EXR of the particle surface (t, normal), or empty
  std::string dump_layers;             // directory for frame 0's brick images, or empty
  bool psnr = false;                   // --stats also carries each frame's PSNR vs the reference
  int max_frames = 0;                  // only the first N of an orbit's frames (0: all)
  std::string steps;                   // --steps: "all", "A:B" or "A:B:S" (empty: time.step only)
  bool quiet = false;
  bool sync_output = false;            // write each frame before the next renders (benchmarks)
};

// Returns the process exit code (0 on success). Collective over `comm`.
int runRenderJob(const RenderOptions& opts, MPI_Comm comm);

// --steps SPEC of a scene with `steps` time steps: "all", "A:B" (A to B, both included) or "A:B:S"
// (every S-th from A, up to B). Throws InputError naming --steps. `steps` < 0: the count is not
// known yet (only the syntax and A >= 0 are checked).
std::vector<int> parseSteps(const std::string& spec, int steps);

// The scene's cameras, cut to the first `max_frames` (0: all).
std::vector<Camera> firstFrames(std::vector<Camera> cameras, int max_frames);

}  // namespace sortlast
