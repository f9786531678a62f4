#include "session/volume_loading.h"

#include <algorithm>
#include <limits>

#include "session/collective.h"
#include "common/build_features.h"
#include "session/hdf5_loading.h"

namespace sortlast {

namespace {
constexpr int kScatterTag = 201;
}

std::vector<std::vector<float>> loadOwnBricks(const VolumeDesc& desc, const std::vector<Brick>& bricks,
                                              const std::vector<int>& mine,
                                              const Assignment& assignment, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<std::vector<float>> out(mine.size());
  // (A format the build has no library for was refused by validateVolume, on every rank.)
  if constexpr (build::kHdf5) {
    if (!desc.isProcedural() && desc.formatOf() == VolumeFormat::kHdf5) {  // collectively, MPI-IO
      std::vector<IndexBox> boxes;
      for (int id : mine) boxes.push_back(bricks[size_t(id)].stored);
      return readHdf5Collective(desc, boxes, comm);
    }
  }
  if (!desc.readsWhole()) {  // each rank reads its own bricks
    collectively(comm, [&] {
      for (size_t i = 0; i < mine.size(); ++i) out[i] = readSamples(desc, bricks[mine[i]].stored);
    });
    return out;
  }
  std::vector<float> whole;
  collectively(comm, [&] {
    if (rank == 0) whole = readWholeVolume(desc);
  });
  if (rank == 0) {
    std::vector<std::vector<float>> pending;
    std::vector<MPI_Request> req;
    for (const Brick& b : bricks) {
      int owner = assignment.owner[b.id];
      if (owner == 0) continue;
      // One tag: messages from one sender arrive in order, and owners receive in brick-id order.
      pending.push_back(extractBox(whole, desc.grid.dims, b.stored));
      req.emplace_back();
      MPI_Isend(pending.back().data(), int(pending.back().size()), MPI_FLOAT, owner,
                kScatterTag, comm, &req.back());
    }
    for (size_t i = 0; i < mine.size(); ++i) out[i] = extractBox(whole, desc.grid.dims, bricks[mine[i]].stored);
    MPI_Waitall(int(req.size()), req.data(), MPI_STATUSES_IGNORE);
  } else {
    for (size_t i = 0; i < mine.size(); ++i) {
      out[i].resize(size_t(bricks[mine[i]].stored.count()));
      MPI_Recv(out[i].data(), int(out[i].size()), MPI_FLOAT, 0, kScatterTag, comm,
               MPI_STATUS_IGNORE);
    }
  }
  return out;
}

std::pair<double, double> globalRange(const std::vector<std::vector<float>>& local,
                                      const std::string& file, MPI_Comm comm) {
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (const auto& s : local) widenRange(s.data(), s.size(), lo, hi);  // missing samples left out
  double in[2] = {lo, -double(hi)}, res[2];
  MPI_Allreduce(in, res, 2, MPI_DOUBLE, MPI_MIN, comm);
  // The same answer on every rank, so every rank throws or none.
  if (!(res[0] <= -res[1]))
    throw InputError(allSamplesMissing(file));
  return {res[0], -res[1]};
}

}  // namespace sortlast
