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

class RadixK final : public Compositor {
 public:
  explicit RadixK(int k);  // k >= 2
  ImageRGBA8 composite(std::vector<BrickImage> mine, const VisibilityOrder& order, int width,
                       int height, MPI_Comm comm, CompositeStats& stats) override;

 private:
  int k_;
};

// The strategy over any transport (MPI in RadixK::composite, threads in the unit tests).
ImageRGBA8 radixKComposite(std::vector<BrickImage> mine, const VisibilityOrder& order, int width,
                           int height, int k, Transport& transport, CompositeStats& stats);

}  // namespace sortlast
