#pragma once
// A compositing strategy: takes each rank's encoded brick images and leaves the finished frame on
// rank 0. One strategy per file behind this one interface (IceT's layout); the blending itself is
// in blend.h and knows nothing of MPI.
#include <memory>
#include <string>
#include <vector>

#include <mpi.h>

#include "common/image.h"
#include "compositing/brick_image.h"

namespace sortlast {

struct CompositeStats {
  double transfer_s = 0.0;   // waiting for and receiving images (rank 0) or sending them
  double composite_s = 0.0;  // decoding and blending (rank 0)
};

class Compositor {
 public:
  virtual ~Compositor() = default;
  // `mine`: this rank's brick images. `order`: every brick id, back to front. Returns the frame
  // on rank 0 and an empty image elsewhere.
  virtual ImageRGBA8 composite(std::vector<BrickImage> mine, const std::vector<int>& order,
                               int width, int height, MPI_Comm comm, CompositeStats& stats) = 0;
};

std::unique_ptr<Compositor> makeCompositor(const std::string& strategy);

}  // namespace sortlast
