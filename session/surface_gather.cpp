#include "session/surface_gather.h"

#include <limits>

namespace sortlast {

SurfaceImage gatherSurface(const std::vector<SurfacePiece>& mine, int width, int height, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  // One float message per rank: for each piece x, y, w, h (exact in float below 2^24), then data.
  std::vector<float> packed;
  for (const SurfacePiece& p : mine) {
    // A brick without surface floats (no opaque surface in it) sends nothing.
    if (p.rect.empty() || p.data.size() != size_t(p.rect.area()) * 4) continue;
    packed.insert(packed.end(), {float(p.rect.x), float(p.rect.y), float(p.rect.w), float(p.rect.h)});
    packed.insert(packed.end(), p.data.begin(), p.data.end());
  }
  int count = int(packed.size());
  std::vector<int> counts(static_cast<size_t>(size)), displs(static_cast<size_t>(size));
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::vector<float> all;
  if (rank == 0) {
    int total = 0;
    for (int r = 0; r < size; ++r) displs[size_t(r)] = total, total += counts[size_t(r)];
    all.resize(size_t(total));
  }
  MPI_Gatherv(packed.data(), count, MPI_FLOAT, all.data(), counts.data(), displs.data(), MPI_FLOAT, 0, comm);
  if (rank != 0) return {};
  SurfaceImage out(width, height);
  for (size_t i = 0; i < all.size();) {
    Rect r{int(all[i]), int(all[i + 1]), int(all[i + 2]), int(all[i + 3])};
    i += 4;
    for (int y = 0; y < r.h; ++y)
      for (int x = 0; x < r.w; ++x, i += 4) {
        float t = all[i];
        if (t >= 1e29f) continue;
        size_t px = size_t(r.y + y) * width + size_t(r.x + x);
        if (!(t < out.t[px])) continue;
        out.t[px] = t;
        out.normal[px] = {all[i + 1], all[i + 2], all[i + 3]};
      }
  }
  return out;
}

}  // namespace sortlast
