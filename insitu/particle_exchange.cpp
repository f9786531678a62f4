#include "insitu/particle_exchange.h"

#include <cmath>
#include <string>

#include "common/error.h"

namespace sortlast {

namespace {

glm::dvec3 positionOf(const ParticleBlock& b, long long i) {
  const long long k = i * b.stride;
  if (b.x) return {b.x[k], b.y[k], b.z[k]};
  return {b.x32[k], b.y32[k], b.z32[k]};
}

double distanceToBox(const glm::dvec3& p, const Box3& b) {
  glm::dvec3 d = glm::max(glm::max(b.lo - p, p - b.hi), glm::dvec3(0.0));
  return glm::length(d);
}

}  // namespace

ParticleExtent gatherParticleExtent(const ParticleBlock& mine, const glm::dvec3& shift, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string problem;
  if (mine.count < 0) problem = "a negative particle count";
  else if (mine.count > 0 && !((mine.x && mine.y && mine.z) || (mine.x32 && mine.y32 && mine.z32)))
    problem = "particles without x, y and z pointers";
  else if (mine.count > 0 && mine.stride < 1) problem = "a particle stride below 1";
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (long long i = 0; problem.empty() && i < mine.count; ++i) {
    glm::dvec3 p = positionOf(mine, i);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      problem = "particle " + std::to_string(i) + " has a NaN or infinite position";
      break;
    }
    p -= shift;
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  }
  double in[7] = {lo[0], lo[1], lo[2], -hi[0], -hi[1], -hi[2], problem.empty() ? 0.0 : 1.0}, out[7];
  MPI_Allreduce(in, out, 7, MPI_DOUBLE, MPI_MIN, comm);
  long long count = problem.empty() ? mine.count : 0, total = 0;
  MPI_Allreduce(&count, &total, 1, MPI_LONG_LONG, MPI_SUM, comm);
  if (!problem.empty()) throw InputError("rank " + std::to_string(rank) + ": " + problem);
  ParticleExtent e;
  e.total = total;
  if (total > 0) e.bounds = {{out[0], out[1], out[2]}, {-out[3], -out[4], -out[5]}};
  return e;
}

std::vector<glm::vec3> exchangeParticles(const ParticleBlock& mine, const glm::dvec3& shift,
                                         const std::vector<Box3>& regions, double margin, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<std::vector<float>> to(static_cast<size_t>(size));
  for (long long i = 0; i < mine.count; ++i) {
    glm::dvec3 p = positionOf(mine, i) - shift;
    for (int r = 0; r < size; ++r) {
      const Box3& box = regions[size_t(r)];
      if (isEmpty(box) || distanceToBox(p, box) > margin) continue;
      to[size_t(r)].insert(to[size_t(r)].end(), {float(p.x), float(p.y), float(p.z)});
    }
  }
  const size_t n = static_cast<size_t>(size);
  std::vector<int> send_counts(n), send_displs(n), recv_counts(n), recv_displs(n);
  std::vector<float> send;
  for (int r = 0; r < size; ++r) {
    send_displs[size_t(r)] = int(send.size());
    send_counts[size_t(r)] = int(to[size_t(r)].size());
    send.insert(send.end(), to[size_t(r)].begin(), to[size_t(r)].end());
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm);
  int total = 0;
  for (int r = 0; r < size; ++r) recv_displs[size_t(r)] = total, total += recv_counts[size_t(r)];
  std::vector<float> recv(static_cast<size_t>(total));
  MPI_Alltoallv(send.data(), send_counts.data(), send_displs.data(), MPI_FLOAT, recv.data(),
                recv_counts.data(), recv_displs.data(), MPI_FLOAT, comm);
  std::vector<glm::vec3> out(recv.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {recv[3 * i], recv[3 * i + 1], recv[3 * i + 2]};
  return out;
}

}  // namespace sortlast
