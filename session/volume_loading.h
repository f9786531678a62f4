#pragma once
// Getting each rank its own bricks' samples, and nothing more. Every format but legacy .vtk is read
// by each rank for its bricks only (readSamples; HDF5 collectively through MPI-IO,
// session/hdf5_loading.h); legacy .vtk is read whole by rank 0 and the bricks sent to their
// owners (VTK's legacy reader cannot read a part).
#include <mpi.h>

#include <vector>

#include "common/brick.h"
#include "common/decomposition.h"
#include "io/volume_source.h"

namespace sortlast {

// Samples of each brick in `mine` (same order), stored box with ghosts. Collective.
std::vector<std::vector<float>> loadOwnBricks(const VolumeDesc& desc, const std::vector<Brick>& bricks,
                                              const std::vector<int>& mine,
                                              const Assignment& assignment, MPI_Comm comm);

// Global [min, max] over all ranks' samples, missing ones (NaN) left out. Collective; throws
// InputError naming `file` on every rank when every sample is missing.
std::pair<double, double> globalRange(const std::vector<std::vector<float>>& local,
                                      const std::string& file, MPI_Comm comm);

}  // namespace sortlast
