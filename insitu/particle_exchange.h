#pragma once
// The simulation's particles, wherever each rank holds them, sent to the ranks whose regions they
// can reach: each rank gets the particles within `margin` (the influence radius h) of its region,
// as float positions in sortlast's world (the simulation's minus `shift`), ordered by the rank that
// published them and then by their index, so every decomposition sums each point's field in the
// same order (the order a file written rank after rank has).
#include <mpi.h>

#include <vector>

#include <glm/glm.hpp>

#include "common/box.h"
#include "sortlast/insitu.h"

namespace sortlast {

// Collective. Bounds of every rank's particle centres (in sortlast's world) and their total count;
// throws InputError naming the rank and index of a NaN or infinite position.
struct ParticleExtent {
  Box3 bounds = noBox();  // lo > hi: no particle anywhere
  long long total = 0;
};
ParticleExtent gatherParticleExtent(const ParticleBlock& mine, const glm::dvec3& shift, MPI_Comm comm);

// Collective. regions[r]: rank r's region (an empty box: it gets nothing).
std::vector<glm::vec3> exchangeParticles(const ParticleBlock& mine, const glm::dvec3& shift,
                                         const std::vector<Box3>& regions, double margin, MPI_Comm comm);

}  // namespace sortlast
