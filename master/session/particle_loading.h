#pragma once
// Getting each rank the particles it needs: rank 0 loads the set (file or procedural) once and
// sends every rank the particles inside its region plus ghost copies of those within h of it, so a
// rank can evaluate the field exactly anywhere in its region. Order is kept (global order), so
// every rank sums a point's field in the same order as a single rank would.
#include <mpi.h>

#include <vector>

#include <glm/glm.hpp>

#include "common/box.h"
#include "common/particles.h"

namespace sortlast {

struct RootParticles {
  ParticleSet set;     // the whole set on rank 0; empty elsewhere
  Box3 bounds;         // of all centres, on every rank (lo > hi when there are none)
  long long total = 0; // particles in the set, on every rank
};

// Rank 0 loads `desc`; bounds and count reach every rank. Collective; errors end the job on all
// ranks (through collectively()).
RootParticles loadParticlesOnRoot(const ParticleDesc& desc, MPI_Comm comm);

// Rank r receives the particles within `margin` of region[r] (an empty box: none). Collective.
std::vector<glm::vec3> scatterParticles(const RootParticles& root, const std::vector<Box3>& region,
                                        double margin, MPI_Comm comm);

}  // namespace sortlast
