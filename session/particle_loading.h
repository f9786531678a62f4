#pragma once
// Getting each rank the particles it needs. The set is loaded once: whole by rank 0 (files of
// most formats, procedural sets), or by every rank a contiguous share of the file's rows (HDF5
// snapshots: no rank holds the whole set). Then every rank gets the particles inside its region
// plus ghost copies of those within h of it, so a rank can evaluate the field exactly anywhere in
// its region. Order is kept (global order: shares are contiguous and arrive in rank order), so
// every rank sums a point's field in the same order as a single rank would.
#include <mpi.h>

#include <vector>

#include <glm/glm.hpp>

#include "common/box.h"
#include "io/particles.h"

namespace sortlast {

struct LoadedParticles {
  ParticleSet set;     // rank 0: the whole set, others: nothing; or (shared) this rank's share
  bool shared = false; // every rank holds a share (readsInShares)
  Box3 bounds;         // of all centres, on every rank (lo > hi when there are none)
  long long total = 0; // particles in the set, on every rank
};

// Loads `desc` (rank 0, or every rank its share); bounds and count reach every rank. Collective;
// errors end the job on all ranks (through collectively()).
LoadedParticles loadParticleSet(const ParticleDesc& desc, MPI_Comm comm);

// Rank r receives the particles within `margin` of region[r] (an empty box: none). Collective.
std::vector<glm::vec3> scatterParticles(const LoadedParticles& loaded, const std::vector<Box3>& region,
                                        double margin, MPI_Comm comm);

}  // namespace sortlast
