#include "compositing/direct_send.h"

#include <map>
#include <stdexcept>

#include "compositing/blend.h"

namespace sortlast {

namespace {
constexpr int kBrickTag = 101;
}

ImageRGBA8 DirectSend::composite(std::vector<BrickImage> mine, const VisibilityOrder& visibility,
                                 int width, int height, MPI_Comm comm, CompositeStats& stats) {
  const std::vector<int>& order = visibility.bricks;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  double t0 = MPI_Wtime();
  if (rank != 0) {
    std::vector<std::vector<uint8_t>> packed;
    std::vector<MPI_Request> req(mine.size());
    for (size_t i = 0; i < mine.size(); ++i) {
      packed.push_back(packBrickImage(mine[i]));
      stats.bytes_sent += double(packed.back().size());
      MPI_Isend(packed.back().data(), int(packed.back().size()), MPI_BYTE, 0, kBrickTag, comm,
                &req[i]);
    }
    MPI_Waitall(int(req.size()), req.data(), MPI_STATUSES_IGNORE);
    stats.transfer_s = MPI_Wtime() - t0;
    return {};
  }
  std::map<int, BrickImage> by_id;
  for (BrickImage& b : mine) by_id[b.brick_id] = std::move(b);
  size_t expected = order.size();
  std::vector<uint8_t> buf;
  while (by_id.size() < expected) {
    MPI_Status st;
    MPI_Probe(MPI_ANY_SOURCE, kBrickTag, comm, &st);
    int bytes = 0;
    MPI_Get_count(&st, MPI_BYTE, &bytes);
    buf.resize(size_t(bytes));
    MPI_Recv(buf.data(), bytes, MPI_BYTE, st.MPI_SOURCE, kBrickTag, comm, MPI_STATUS_IGNORE);
    BrickImage b = unpackBrickImage(buf);
    if (b.brick_id < 0 || size_t(b.brick_id) >= expected || by_id.count(b.brick_id))
      throw std::runtime_error("direct send: unexpected brick id " + std::to_string(b.brick_id) +
                               " from rank " + std::to_string(st.MPI_SOURCE));
    by_id[b.brick_id] = std::move(b);
  }
  double t1 = MPI_Wtime();
  stats.transfer_s = t1 - t0;
  std::vector<const BrickImage*> ordered;
  for (int id : order) ordered.push_back(&by_id.at(id));
  // Blended in float and rounded once, like the swap strategies: the frame does not depend on
  // how the blends are grouped.
  ImageF frame(width, height);
  blendBackToFront(ordered, frame);
  ImageRGBA8 out = toRGBA8(frame);
  stats.composite_s = MPI_Wtime() - t1;
  return out;
}

}  // namespace sortlast
