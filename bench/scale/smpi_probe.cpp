// MPI_Probe for the SMPI build. SimGrid implements MPI_Probe as a loop of MPI_Iprobe calls, each
// unsuccessful one sleeping longer in simulated time (smpi/iprobe, 100 us, times the number of
// tries so far): a rank waiting on a probe notices its message late, which inflates the simulated
// times, and thousands of waiting ranks keep the simulator busy polling (a 256-rank run did not
// finish in 10 minutes). The strategies probe only to learn a message's size before receiving it
// (mpi_transport.cpp, direct_send.cpp), so here MPI_Probe receives the message itself into a
// per-rank buffer (address space reserved, pages touched only as far as the message reaches) and
// the MPI_Recv that follows copies it out: the simulated transfer is the same one message, and the
// wait ends when it has arrived, as with a real rendezvous probe and receive.
#include "bench/scale/smpi_probe.h"

#include <sys/mman.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

constexpr size_t kCapacity = size_t(1) << 30;  // the largest message a probe can take
constexpr int kMaxRanks = 1 << 16;

struct Probed {
  uint8_t* buffer = nullptr;
  bool full = false;
  MPI_Status status{};
  int bytes = 0;
  MPI_Comm comm = MPI_COMM_NULL;
};
// Indexed by rank in MPI_COMM_WORLD: SMPI runs every rank in one process with shared globals.
Probed g_probed[kMaxRanks];

int worldRank() {
  int r = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

[[noreturn]] void die(const char* what) {
  std::fprintf(stderr, "bench_scale (SMPI probe): %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int MPI_Probe(int source, int tag, MPI_Comm comm, MPI_Status* status) {
  Probed& p = g_probed[worldRank()];
  if (p.full) die("two probes without a receive between them");
  if (!p.buffer) {
    void* m = mmap(nullptr, kCapacity, PROT_READ | PROT_WRITE,
                   MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (m == MAP_FAILED) die("cannot reserve the probe buffer");
    p.buffer = static_cast<uint8_t*>(m);
  }
  const int rc = PMPI_Recv(p.buffer, int(std::min<size_t>(kCapacity, INT_MAX)), MPI_BYTE, source,
                           tag, comm, &p.status);
  if (rc != MPI_SUCCESS) return rc;
  PMPI_Get_count(&p.status, MPI_BYTE, &p.bytes);
  p.full = true;
  p.comm = comm;
  if (status != MPI_STATUS_IGNORE) *status = p.status;
  return MPI_SUCCESS;
}

bool sortlast::scale::receiveProbed(void* buf, int count, MPI_Datatype type, int source, int tag,
                                    MPI_Comm comm, MPI_Status* status) {
  Probed& p = g_probed[worldRank()];
  if (!p.full || comm != p.comm || (source != MPI_ANY_SOURCE && source != p.status.MPI_SOURCE) ||
      (tag != MPI_ANY_TAG && tag != p.status.MPI_TAG))
    return false;
  if (type != MPI_BYTE || count < p.bytes) die("a probed message received as other than its bytes");
  std::memcpy(buf, p.buffer, size_t(p.bytes));
  p.full = false;
  if (status != MPI_STATUS_IGNORE) *status = p.status;
  return true;
}
