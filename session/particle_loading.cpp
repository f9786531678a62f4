#include "session/particle_loading.h"

#include "session/collective.h"

namespace sortlast {

namespace {

// Positions as floats, three per particle, for MPI.
void pack(const std::vector<glm::vec3>& ps, std::vector<float>& out) {
  for (const glm::vec3& p : ps) out.insert(out.end(), {p.x, p.y, p.z});
}

std::vector<glm::vec3> unpack(const std::vector<float>& in) {
  std::vector<glm::vec3> out(in.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {in[3 * i], in[3 * i + 1], in[3 * i + 2]};
  return out;
}

}  // namespace

LoadedParticles loadParticleSet(const ParticleDesc& desc, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  LoadedParticles out;
  out.shared = size > 1 && readsInShares(desc);
  long long total = 0;
  collectively(comm, [&] {
    if (out.shared) out.set = loadParticleShare(desc, rank, size, &total);
    else if (rank == 0) out.set = loadParticles(desc);
  });
  const Box3 b = out.set.bounds();
  if (out.shared) {
    // Each rank's share: the bounds and count of all of them.
    double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
    MPI_Allreduce(MPI_IN_PLACE, lo, 3, MPI_DOUBLE, MPI_MIN, comm);
    MPI_Allreduce(MPI_IN_PLACE, hi, 3, MPI_DOUBLE, MPI_MAX, comm);
    out.bounds = {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
    out.total = total;
    return out;
  }
  double msg[7] = {b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z, double(out.set.positions.size())};
  MPI_Bcast(msg, 7, MPI_DOUBLE, 0, comm);
  out.bounds = {{msg[0], msg[1], msg[2]}, {msg[3], msg[4], msg[5]}};
  out.total = (long long)msg[6];
  return out;
}

std::vector<glm::vec3> scatterParticles(const LoadedParticles& loaded, const std::vector<Box3>& region,
                                        double margin, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  // What this rank sends to each rank r: the particles it holds near region[r], in their order.
  std::vector<int> counts(size_t(size), 0), displs(size_t(size), 0);
  std::vector<float> packed;
  if (loaded.shared || rank == 0) {
    for (int r = 0; r < size; ++r) {
      const Box3& box = region[size_t(r)];
      displs[size_t(r)] = int(packed.size());
      if (!isEmpty(box)) pack(particlesNear(loaded.set.positions, box, margin), packed);
      counts[size_t(r)] = int(packed.size()) - displs[size_t(r)];
    }
  }
  if (!loaded.shared) {
    int mine = 0;
    MPI_Scatter(counts.data(), 1, MPI_INT, &mine, 1, MPI_INT, 0, comm);
    std::vector<float> received(static_cast<size_t>(mine));
    MPI_Scatterv(packed.data(), counts.data(), displs.data(), MPI_FLOAT, received.data(), mine, MPI_FLOAT, 0, comm);
    return unpack(received);
  }
  // Shares: every rank sends to every rank; received in source order, which is the file's order.
  std::vector<int> in_counts(size_t(size), 0), in_displs(size_t(size), 0);
  MPI_Alltoall(counts.data(), 1, MPI_INT, in_counts.data(), 1, MPI_INT, comm);
  long long in_total = 0;
  for (int r = 0; r < size; ++r) in_displs[size_t(r)] = int(in_total), in_total += in_counts[size_t(r)];
  std::vector<float> received(static_cast<size_t>(in_total));
  MPI_Alltoallv(packed.data(), counts.data(), displs.data(), MPI_FLOAT, received.data(), in_counts.data(),
                in_displs.data(), MPI_FLOAT, comm);
  return unpack(received);
}

}  // namespace sortlast
