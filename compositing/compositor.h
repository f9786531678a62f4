#pragma once
// A compositing strategy: takes each rank's encoded brick images and leaves the finished frame on
// rank 0. One strategy per file behind this one interface (IceT's layout); the blending itself is
// in blend.h and knows nothing of MPI.
//
// A frame is begin(), then add() for each of this rank's brick images as soon as it is rendered,
// then finish(). A strategy that can overlap its messages with rendering (direct send) starts
// sending in add(); the swap strategies need every brick of a rank first and do all in finish().
#include <mpi.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/image.h"
#include "scene/sections.h"
#include "compositing/brick_image.h"
#include "compositing/rect_image.h"
#include "common/visibility.h"

namespace sortlast {

struct CompositeStats {
  double transfer_s = 0.0;   // sending, waiting for and receiving images
  double composite_s = 0.0;  // decoding, blending and (swap strategies) encoding
  double bytes_sent = 0.0;   // bytes this rank sent, message headers included
};

// How partial results are held: Precision, the scene's compositing.precision
// (scene/sections.h says what each means).
struct CompositeOptions {
  Precision precision = Precision::kFloat;
  // Direct send: send each brick image as soon as it is rendered and let rank 0 blend images as
  // their visibility order allows. False: everything is sent after the last brick (for measuring
  // what overlap gains).
  bool overlap = true;
  // Rank 0 also wants the frame unrounded (EXR output): the swap strategies then gather their
  // final parts at 16 bits instead of 8.
  bool float_frame = false;
  // Run-length coding of transparent runs (the paper's Fig. 7) on every message; false: each
  // pixel travels (for measuring what RLE gains).
  bool rle = true;
  // Glow scenes (docs/glow.md): brick images and partial composites carry light without opacity,
  // above 1 before the final tone map, as WireFormat::Emission (half floats); precision must be
  // Float and the caller asks for the float frame (the RGBA8 one clamps colour to alpha).
  bool emission = false;
  // Projection blend modes (render.blend: mip, minip, average, additive): brick images and
  // partial composites are this format (compositing/projection_pixels.h), combined by its
  // order-free operator; RGBA8 here: not a projection. precision must be Float.
  WireFormat projection = WireFormat::RGBA8;
  // With a projection: turns `n` combined float pixels (in place) into premultiplied RGBA, once,
  // on the final values: on rank 0 (direct send) or on the rank that makes a final part (radix-k),
  // before it is rounded. An absent pixel (all zero) must stay transparent.
  std::function<void(float* px, size_t n)> colour_projection;
  // `auto` only (strategy_model.h): the network and core sharing its forecasts assume.
  double network_latency_s = 40e-6;       // one message, end to end
  double network_bandwidth_Bps = 1.25e9;  // one rank's link, each way
  double ranks_per_core = 1.0;            // on the busiest node
};

struct FrameFootprint;

// This rank's part of one frame.
struct FrameSetup {
  const VisibilityOrder* order = nullptr;  // every brick and every rank, back to front
  int brick_count = 0;                     // bricks this rank will add()
  int width = 0, height = 0;
  MPI_Comm comm = MPI_COMM_NULL;
  // Every rank's forecast screen rectangles (strategy_model.h), the same on every rank: what
  // `auto` chooses from. The explicit strategies ignore it.
  const FrameFootprint* footprint = nullptr;
};

// What `auto` chose for the last frame, and why (--stats).
struct StrategyChoice {
  std::string strategy;  // direct | binary-swap | radix-k
  int radix = 0;         // k, 0 for direct
  std::string label;     // "radix-k k=8"
  double forecast_s = 0;
  std::string why;       // one line: the forecasts compared and what decided
};

class Compositor {
 public:
  virtual ~Compositor() = default;
  virtual void begin(const FrameSetup& setup) = 0;
  // One of this rank's brick images, in any order.
  virtual void add(BrickImage image) = 0;
  // Whether add() takes this rank's images of an Emission frame unencoded (BrickImage::emission):
  // where they are blended here without being sent (direct send's rank 0), which spares the
  // half-float encoding and its decoding.
  virtual bool takesLocalEmission() const { return false; }
  // Called over and over while this rank waits for the others to finish rendering: a chance to
  // take and blend what has arrived. Never throws (errors are reported by finish()).
  virtual void progress() {}
  // Collective over the communicator. Returns the frame on rank 0 and an empty image elsewhere;
  // with options.float_frame, rank 0's `float_frame` (if given) gets the frame before rounding.
  // With options.emission and a `float_frame`, the RGBA8 frame may be left transparent (direct
  // send does: the caller tone-maps the float frame into its own).
  virtual ImageRGBA8 finish(CompositeStats& stats, ImageF* float_frame = nullptr) = 0;
  // Hands back a frame finish() returned, once the caller is done with it (its pixels may be
  // anything): a later finish() fills it instead of a fresh frame-sized image, whose pages the
  // kernel would fault in and zero again every frame. Optional; strategies without a frame of
  // their own ignore it.
  virtual void recycle(ImageRGBA8 frame) { (void)frame; }
  // The frame failed on some rank before finish(). Called on every rank: completes or drains the
  // messages already under way, so every rank can stop without a message left unmatched.
  virtual void abandon() = 0;
  // `auto`: the strategy this frame runs; nullptr for the explicit strategies.
  virtual const StrategyChoice* choice() const { return nullptr; }

  // begin, add each of `mine`, finish.
  ImageRGBA8 composite(std::vector<BrickImage> mine, const VisibilityOrder& order, int width,
                       int height, MPI_Comm comm, CompositeStats& stats,
                       const FrameFootprint* footprint = nullptr);
};

// `strategy`: direct | binary-swap | radix-k (with `radix` partners per round, >= 2) | auto (the
// fastest by the cost model, each frame, from direct send and radix-k with k = 2 ... 32; `radix`
// is then not used).
std::unique_ptr<Compositor> makeCompositor(Strategy strategy, int radix, const CompositeOptions& options = {});
// The same by the strategy's name (compositing.strategy's names); throws std::invalid_argument on
// another name.
std::unique_ptr<Compositor> makeCompositor(const std::string& strategy, int radix,
                                           const CompositeOptions& options = {});

}  // namespace sortlast
