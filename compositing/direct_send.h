#pragma once
// Direct send (the paper's scheme): every rank sends each brick image to rank 0, which blends all
// of them in visibility order (in float, rounded to RGBA8 once). Simple and exact, but rank 0
// receives everything: it does not scale.
#include "compositing/compositor.h"

namespace sortlast {

class DirectSend final : public Compositor {
 public:
  ImageRGBA8 composite(std::vector<BrickImage> mine, const VisibilityOrder& order, int width,
                       int height, MPI_Comm comm, CompositeStats& stats) override;
};

}  // namespace sortlast
