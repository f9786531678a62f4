#pragma once
// Memory bounds before allocation: what a scene will need on a rank (its bricks' samples with
// ghosts, their textures, the particle copies and metaball grids, the image targets and
// compositing buffers, the step cache) against what the rank may use (limits.memory_mib, or a
// share of MemAvailable). A scene that cannot fit is refused with the figures, on every rank,
// before the first large allocation, instead of running for minutes or ending in std::bad_alloc.
// The estimates are upper bounds of the large items only (a few MiB of code and GL state aside).
#include <mpi.h>

#include <string>
#include <vector>

#include "scene/scene.h"
#include "render/gl/gl_context.h"
#include "session/session_layout.h"

namespace sortlast {

struct MemoryPart {
  std::string what;
  double bytes = 0;
  // Of `bytes`, what a GPU holds in its own memory (textures, render targets, storage buffers).
  // `bytes` counts them too: on llvmpipe they are host memory, and on a GPU the driver may keep
  // host copies, so the host check stays an upper bound either way.
  double gpu_bytes = 0;
};

struct MemoryNeed {
  std::vector<MemoryPart> parts;
  double total() const;
  void add(std::string what, double bytes, double gpu_bytes = 0);
  // The parts a GPU holds, with their GPU bytes (for checkMemory against a GPU budget).
  MemoryNeed onGpu() const;
};

// What one rank may use, and where the figure comes from (for the message).
struct MemoryBudget {
  double bytes = 0;
  std::string source;
  // Which bound set it (--stats): "limits.memory_mib", "cgroup" (the job's memory limit on this
  // node), "MemAvailable", "gpu" or "unknown".
  std::string bound;
};

// Share of MemAvailable a rank may plan for: the rest is for the system, the MPI library, the
// GL driver's own copies and the estimate's error.
constexpr double kMemorySafety = 0.9;

// limits.memory_mib, else kMemorySafety x the smaller of MemAvailable and the cgroup's memory limit
// (cgroup_memory.h: a batch job's limit on this node, which all its ranks there share) / the ranks
// of this job on this node. Collective (counts the node's ranks).
MemoryBudget memoryBudget(const Scene& scene, MPI_Comm comm);

// Rank 0's copy of the whole particle set, before it is loaded (procedural count, or the file's
// size as a bound); for a set read in shares (readsInShares) on `ranks` > 1, one rank's share.
MemoryNeed particleSetNeed(const Scene& scene, int ranks);
// Image targets and compositing buffers for a w x h frame on one rank.
MemoryNeed imageNeed(const Scene& scene, int width, int height, int rank, int bricks_here,
                     int bricks_all);
// Everything a rank of a session holds for the scene.
MemoryNeed sessionNeed(const Scene& scene, const SessionLayout& layout, long long particles,
                       int rank, bool resident);

// What a rank may put in its GPU's memory: 90% of what the driver reports free when the context
// is made (GL_NVX_gpu_memory_info, GL_ATI_meminfo), shared by `sharing` ranks of this node on the
// same device; infinite (no check) when the driver reports nothing (llvmpipe, most non-NVIDIA).
// The source names the GPU, its device number and host.
MemoryBudget gpuMemoryBudget(const GlDeviceInfo& gpu, int sharing);

// Throws InputError naming the need, its largest parts and the budget, if need > budget.
void checkMemory(const MemoryNeed& need, const MemoryBudget& budget, int rank,
                 const std::string& what);

}  // namespace sortlast
