#pragma once
// Radix-k compositing (Peterka et al.), binary-swap (Ma et al.) being radix-k with k = 2. Each rank
// first blends its own bricks into one image of the rectangle they cover; the ranks whose image
// is not transparent then follow the schedule of schedule.h: folds, then rounds in which k
// partners split their common region k ways and each composites one part from all of them; at the
// end every part goes to rank 0. Only active rectangles travel, RLE-encoded, and nothing travels
// where the schedule shows that the sender holds no pixel: a rank whose image is transparent
// sends nothing at all.
#include "compositing/compositor.h"
#include "compositing/transport.h"

namespace sortlast {

// Every brick of a rank must be in before its local composite, so add() only collects and the
// whole strategy runs in finish(): nothing to overlap with rendering.
class RadixK final : public Compositor {
 public:
  RadixK(int k, const CompositeOptions& options);  // k >= 2
  void begin(const FrameSetup& setup) override;
  void add(BrickImage image) override { mine_.push_back(std::move(image)); }
  ImageRGBA8 finish(CompositeStats& stats, ImageF* float_frame) override;
  void abandon() override { mine_.clear(); }  // nothing was sent before finish()

 private:
  int k_;
  CompositeOptions opt_;
  FrameSetup setup_;
  std::vector<BrickImage> mine_;
};

// The strategy over any transport (MPI in RadixK::finish, threads in the unit tests). With
// options.float_frame, rank 0's `float_frame` (if given) gets the frame before rounding.
ImageRGBA8 radixKComposite(std::vector<BrickImage> mine, const VisibilityOrder& order, int width,
                           int height, int k, Transport& transport, CompositeStats& stats,
                           const CompositeOptions& options = {}, ImageF* float_frame = nullptr);

}  // namespace sortlast
