#pragma once
// `--surface-out`: the particle surface of a frame (t and normal per pixel) as one image on rank 0.
// Every rank sends its bricks' surface rectangles; the nearest t wins per pixel (surfaces are
// opaque, so the nearest is the one the frame shows).
#include <mpi.h>

#include <vector>

#include "common/camera.h"
#include "io/surface_image.h"

namespace sortlast {

struct SurfacePiece {
  Rect rect;
  std::vector<float> data;  // rect.w x rect.h x (t, nx, ny, nz); t >= 1e30: miss
};

// The merged surface on rank 0 (an empty image elsewhere). Collective.
SurfaceImage gatherSurface(const std::vector<SurfacePiece>& mine, int width, int height, MPI_Comm comm);

}  // namespace sortlast
