#pragma once
// The compositing cost model behind `compositing.strategy: auto`: a forecast of one frame's
// compositing time under each strategy, from what every rank knows before rendering (the rank
// count, the image size, each rank's forecast screen rectangle and brick pixels, the visibility
// order) and three kinds of figure: the per-pixel rates of the compositing kernels on one core
// (pixel_rates.h), the network's latency and per-link bandwidth, and how many ranks share a core.
//
// It is not a fit. It walks each strategy as the strategy will run: direct send's rank 0 decodes
// and blends every brick image, clears and rounds the frame; radix-k (binary-swap is k = 2) builds
// the very plan radix_k.cpp builds (radix_k_plan.h) from the forecast rectangles and, round by
// round, counts the pixels each unit encodes, decodes and blends and the bytes it sends and
// receives, taking the slowest unit of each round; then rank 0's gather. Pixels are charged at the
// measured rates, bytes at the link bandwidth, each round a latency. What it leaves out: RLE's
// savings in bytes (an upper bound: rectangles, not the pixels that show), network contention
// beyond one link per rank, and direct send's overlap with rendering (it forecasts the compositing
// that is left after the last brick, as bench_scale measures it). docs/smpi.md compares it with
// the simulated sweep.
//
// Deterministic: the same inputs give the same choice on every rank, with no message.
#include <string>
#include <utility>
#include <vector>

#include "common/camera.h"
#include "compositing/compositor.h"
#include "compositing/pixel_rates.h"
#include "common/visibility.h"

namespace sortlast {

struct NetworkModel {
  double latency_s = 40e-6;       // one message, end to end (10 GbE: two 20 us hops)
  double bandwidth_Bps = 1.25e9;  // one rank's link, each way (10 Gbit/s)
};

// What the model knows of each rank's part of a frame, indexed by rank.
struct FrameFootprint {
  std::vector<Rect> rect;            // the union of its brick images' rectangles (empty: none)
  std::vector<double> brick_pixels;  // the sum of their areas
  std::vector<int> bricks;           // how many brick images it adds (direct send: messages)
  bool operator==(const FrameFootprint&) const = default;
};

struct ModelSettings {
  NetworkModel network;
  PixelRates rates = measuredPixelRates();
  double ranks_per_core = 1.0;  // on the busiest node; above 1 the swap strategies' ranks share cores
  bool first_frame = false;     // direct send: nothing of a previous frame to clear
};

struct StrategyForecast {
  std::string strategy;  // direct | binary-swap | radix-k
  int radix = 0;         // k (2 for binary-swap, 0 for direct)
  double seconds = 0;    // the forecast
  double compute_s = 0;  // of which per-pixel work on the critical path
  // Phases on the critical path, in order (name, seconds), for --stats.
  std::vector<std::pair<std::string, double>> phases;
  std::string label() const;  // "direct", "binary-swap", "radix-k k=8"
};

// Every candidate: direct send, then radix-k with each k of `radices` (2 is named binary-swap).
// `order.ranks` and the footprint's vectors hold every rank of the communicator.
std::vector<StrategyForecast> forecastStrategies(const VisibilityOrder& order,
                                                 const FrameFootprint& footprint, int width,
                                                 int height, const CompositeOptions& options,
                                                 const ModelSettings& model,
                                                 const std::vector<int>& radices = {2, 4, 8, 16});

// The fastest forecast; on a tie within 1e-12 s the later candidate: the larger k. Radix-k ties
// when both k give the same plan for the forecast's participants; the ranks that really show
// something may be fewer (a brick whose box is on screen can render nothing), and for any count
// the larger k folds no more ranks (the engine at 64 simulated hosts: k = 16 took 54 % longer
// than k = 32 where the forecast tied them).
const StrategyForecast& fastest(const std::vector<StrategyForecast>& forecasts);

}  // namespace sortlast
