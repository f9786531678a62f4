#pragma once
// A compositing strategy: takes each rank's encoded brick images and leaves the finished frame on
// rank 0. One strategy per file behind this one interface (IceT's layout); the blending itself is
// in blend.h and knows nothing of MPI.
#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

#include "common/image.h"
#include "compositing/brick_image.h"
#include "compositing/visibility.h"

namespace sortlast {

struct CompositeStats {
  double transfer_s = 0.0;   // sending, waiting for and receiving images
  double composite_s = 0.0;  // decoding, blending and (swap strategies) encoding
  double bytes_sent = 0.0;   // bytes this rank sent, message headers included
};

class Compositor {
 public:
  virtual ~Compositor() = default;
  // `mine`: this rank's brick images. `order`: every brick and every rank, back to front. Returns
  // the frame on rank 0 and an empty image elsewhere. Collective over `comm`.
  virtual ImageRGBA8 composite(std::vector<BrickImage> mine, const VisibilityOrder& order,
                               int width, int height, MPI_Comm comm, CompositeStats& stats) = 0;
};

// `strategy`: direct | binary-swap | radix-k (with `radix` partners per round, >= 2).
std::unique_ptr<Compositor> makeCompositor(const std::string& strategy, int radix);

}  // namespace sortlast
