#pragma once
// Which node and GPU each rank renders on: the node-local rank that `render.device: auto` maps to
// a device, every rank's GL identity gathered on rank 0 (--stats, /api/scene), and the number of
// a node's ranks that share one GPU (its memory budget is split between them).
#include <mpi.h>

#include <vector>

#include <nlohmann/json.hpp>

#include "render/gl/gl_context.h"

namespace sortlast {

// This rank's index among the ranks of its node (MPI_COMM_TYPE_SHARED), and how many ranks the
// node has. Collective.
struct NodePlace {
  int rank = 0, size = 1;
};
NodePlace nodePlace(MPI_Comm comm);
inline int nodeLocalRank(MPI_Comm comm) { return nodePlace(comm).rank; }

// How many ranks of this node render on the same hardware device as this one (1 for software
// rendering: llvmpipe has no device memory of its own). Collective.
int ranksSharingDevice(const GlDeviceInfo& mine, MPI_Comm comm);

// Ranks per core on the busiest node: the node's ranks over the cores this process may run on
// (sched_getaffinity), the largest over all nodes, on every rank. Collective.
double ranksPerCore(MPI_Comm comm);

// Every rank's identity, on rank 0 (index = rank); empty elsewhere. Collective.
std::vector<GlDeviceInfo> gatherDeviceInfo(const GlDeviceInfo& mine, MPI_Comm comm);

// {"rank", "host", "backend", "device", "devices", "vendor", "renderer", "version",
//  "gpu_memory_mib": {"total", "free", "source"} or null}
nlohmann::json deviceJson(const GlDeviceInfo& info, int rank);
nlohmann::json deviceJson(const std::vector<GlDeviceInfo>& all);  // an array, by rank

}  // namespace sortlast
