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
  bool quiet = false;
  bool sync_output = false;            // write each frame before the next renders (benchmarks)
};

// Returns the process exit code (0 on success). Collective over `comm`.
int runRenderJob(const RenderOptions& opts, MPI_Comm comm);

// The scene's cameras, cut to the first `max_frames` (0: all).
std::vector<Camera> firstFrames(std::vector<Camera> cameras, int max_frames);

}  // namespace sortlast
