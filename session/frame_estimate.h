#pragma once
// The frame's own accuracy, estimated while it renders (render.estimate): a stratified sample of
// the frame's pixels is integrated with the exact model (reference/ray_segment.h: the reference's
// double-precision emission-absorption integral, not pre-integrated, so the estimate sees what
// the step, pre-integration, early termination, the tables and 8-bit rounding cost) and compared
// with the frame as written (8-bit, over the background).
//
// Collective and distributed like the frame: every rank integrates its own bricks' segments of
// the sampled rays; rank 0 composites each ray's segments front to back (by where they start
// along the ray: the bricks are convex and meet face to face) and compares.
//
// Sampling: the image is cut into square tiles (strata) over the volume's screen rectangle; each
// tile gets samples in proportion to its pixels times (its contrast + the mean contrast), where
// contrast is the frame's mean luminance gradient in the tile (errors gather where the colour
// changes fast: rims, thin shells), at least 2 per tile; pixels outside the rectangle see only
// the background and count as exact. The estimate of the mean squared error and of the share of
// pixels over 4/255 is the stratified mean, its variance the stratified one (with the finite
// population correction); the 95 % bounds are mean +- 1.96 standard errors, mapped to dB.
// Deterministic: the same frame gives the same sample and estimate.
//
// Cost (results/accuracy/estimate_cost.md, 512², 1 rank, llvmpipe on the 2-core machine, against
// the frame's total_s): 11 % on the default scene and the head CT, 12 % on neghip, 22 % on the
// engine, 23 % on hydrogen under a log scale, 26-34 % shaded (the goal is 5 %), since the
// crossings are integrated by adaptive Simpson (reference/ray_segment.h): 1.1-4.1x less than the
// reference's fixed steps took.
#include <mpi.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/camera.h"
#include "common/clip.h"
#include "io/image.h"
#include "reference/ray_segment.h"
#include "scene/scene.h"
#include "session/session_layout.h"
#include "session/step_data.h"

namespace sortlast {

// The pixels sampled (rank 0 chooses; every rank receives them).
struct EstimateSample {
  int width = 0, height = 0;
  std::vector<int> pixel;       // y * width + x
  std::vector<int> stratum;     // per sampled pixel, its tile
  std::vector<double> tile_pixels;  // per tile, pixels in it (N_t)
  std::vector<int> tile_samples;    // per tile, samples in it (n_t)
};

// Chooses about `budget` pixels of `frame` (premultiplied RGBA8, composited over `background`
// for the contrast) inside `rect` (the volume's screen rectangle, common/camera.h screenRectOf).
EstimateSample chooseEstimatePixels(const ImageRGBA8& frame, const glm::dvec3& background,
                                    const Rect& rect, int budget);

// What one rank integrates: its bricks' fields (the samples must outlive the call).
struct EstimateVolume {
  std::vector<BrickField> bricks;
  std::vector<Box3> boxes;  // each brick's world box (its domain's)
  std::vector<EmptyBlocks> empty;  // each brick's blocks without opacity
  TransferFunction tf;
  Shading shading;
  ClipRegion clip;
  double step = 0.0;  // world units (the reference's: reference.step x the smallest spacing)
};

// The exact colour of each sampled pixel over the background, in [0, 1] per channel (rank 0;
// empty elsewhere). Collective over `comm`.
std::vector<double> exactSampledPixels(const EstimateSample& sample, const Camera& cam,
                                       const EstimateVolume& mine, const glm::dvec3& background,
                                       int threads, MPI_Comm comm);

// Sends rank 0's sample to every rank. Collective.
void broadcastSample(EstimateSample& sample, MPI_Comm comm);

struct AccuracyEstimate {
  double mse = 0.0;            // per channel, in (1/255)^2, over the whole frame
  double mse_se = 0.0;         // its standard error
  double over4_share = 0.0;    // pixels with a channel more than 4/255 off
  double over4_se = 0.0;
  int largest_seen = 0;        // the largest channel difference among the sampled pixels
  int sampled = 0;
  double rule_of_three = 1.0;  // over4Hi's floor
  double psnr_db() const;      // infinity for mse 0
  double psnrLo() const;       // 95 % bounds
  double psnrHi() const;
  double over4Hi() const;      // 95 % upper bound (never below 3 / sampled, the rule of three,
                               // times the share of the tiles' pixels not sampled, times the
                               // tiles' share of the frame)
  double over4Lo() const;
  nlohmann::json json() const;
};

// Compares `frame` (premultiplied RGBA8, as the session returns it) at the sampled pixels with
// the exact values. `float_frame` instead when non-null (a probe: premultiplied float, rounded as
// writing it would).
AccuracyEstimate compareWithExact(const EstimateSample& sample, const std::vector<double>& exact,
                                  const ImageRGBA8* frame, const ImageF* float_frame,
                                  const glm::dvec3& background);

// Why a scene's frames get no estimate ("" where they can): what the exact segments do not model.
std::string estimateUnavailable(const Scene& sc, bool adaptive, bool in_situ, const StepData* d);

// The empty-block maps of the last estimate, kept for the next: they depend on the samples, the
// transfer function as built, the reference's step and shading, not on the camera, the image or
// the frame's own step (a fifth of the engine's estimate at 512², perf). `data` is the caller's
// name for the samples: a new one whenever they may have changed.
struct EmptyBlocksCache {
  long long data = -1;
  std::vector<double> key;
  std::vector<EmptyBlocks> empty;
};

// This rank's bricks as the estimate reads them (d.samples must outlive it), the transfer function
// built as the renderer's is (over `range`, the data's on every rank). With `cache`, the block
// maps are taken from it where `data_id` and the function, step and shading are the ones it
// holds, else built and kept there.
EstimateVolume estimateVolumeOf(const Scene& sc, const SessionLayout& layout, const StepData& d,
                                std::pair<double, double> range, EmptyBlocksCache* cache = nullptr,
                                long long data_id = -1);

// The whole estimate of one frame: rank 0 chooses the pixels from its frame (`frame`, or
// `float_frame` where non-null), every rank integrates its segments, rank 0 compares. Returns
// rank 0's `accuracy_estimate` JSON (with `seconds`), null elsewhere. Collective.
nlohmann::json estimateFrame(const EstimateVolume& mine, const Camera& cam, const Box3& volume_box,
                             const glm::dvec3& background, const ImageRGBA8* frame,
                             const ImageF* float_frame, int budget, MPI_Comm comm);

}  // namespace sortlast
