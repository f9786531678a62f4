#include "master/session/particle_loading.h"

#include "master/session/collective.h"

namespace sortlast {

RootParticles loadParticlesOnRoot(const ParticleDesc& desc, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  RootParticles out;
  collectively(comm, [&] {
    if (rank == 0) out.set = loadParticles(desc);
  });
  double msg[7] = {0, 0, 0, 0, 0, 0, 0};
  if (rank == 0) {
    Box3 b = out.set.bounds();
    msg[0] = b.lo.x, msg[1] = b.lo.y, msg[2] = b.lo.z, msg[3] = b.hi.x, msg[4] = b.hi.y, msg[5] = b.hi.z;
    msg[6] = double(out.set.positions.size());
  }
  MPI_Bcast(msg, 7, MPI_DOUBLE, 0, comm);
  out.bounds = {{msg[0], msg[1], msg[2]}, {msg[3], msg[4], msg[5]}};
  out.total = (long long)msg[6];
  return out;
}

std::vector<glm::vec3> scatterParticles(const RootParticles& root, const std::vector<Box3>& region,
                                        double margin, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::vector<int> counts(size_t(size), 0), displs(size_t(size), 0);
  std::vector<float> packed;
  if (rank == 0) {
    for (int r = 0; r < size; ++r) {
      const Box3& box = region[size_t(r)];
      std::vector<glm::vec3> part;
      if (!isEmpty(box)) part = particlesNear(root.set.positions, box, margin);
      displs[size_t(r)] = int(packed.size());
      counts[size_t(r)] = int(part.size() * 3);
      for (const glm::vec3& p : part) packed.insert(packed.end(), {p.x, p.y, p.z});
    }
  }
  int mine = 0;
  MPI_Scatter(counts.data(), 1, MPI_INT, &mine, 1, MPI_INT, 0, comm);
  std::vector<float> received(static_cast<size_t>(mine));
  MPI_Scatterv(packed.data(), counts.data(), displs.data(), MPI_FLOAT, received.data(), mine, MPI_FLOAT, 0, comm);
  std::vector<glm::vec3> out(received.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {received[3 * i], received[3 * i + 1], received[3 * i + 2]};
  return out;
}

}  // namespace sortlast
