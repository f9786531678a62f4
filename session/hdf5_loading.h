#pragma once
// HDF5 volumes in the session: every rank reads its own bricks' boxes (with ghosts) as hyperslabs
// of one dataset, collectively through MPI-IO (Debian's parallel HDF5). Kept apart so that only
// this file and common/hdf5_*.cpp include hdf5.h.
#include <mpi.h>

#include <vector>

#include "common/box.h"
#include "io/volume_source.h"

namespace sortlast {

// The samples of each of this rank's `boxes` (as readSamples returns them). Collective over
// `comm`: the file is opened with the MPI-IO driver on `comm` and every rank makes the same number
// of collective reads (one per box of the rank with the most; a rank with fewer reads empty
// selections). A failure on any rank (allocation, open, read, a NaN) ends every
// rank with JobFailed; a rank that fails keeps making the remaining collective calls with empty
// selections, so no rank is left inside HDF5 waiting for it. volume.mpi_io: independent (and
// auto on one node) makes the reads' transfers independent (the open, the close and the call
// count stay the same).
std::vector<std::vector<float>> readHdf5Collective(const VolumeDesc& desc,
                                                   const std::vector<IndexBox>& boxes, MPI_Comm comm);

// Whether readHdf5Collective's transfers are collective for this volume.mpi_io on these ranks
// (auto: when they span more than one node). Collective.
bool hdf5ReadsCollectively(const VolumeDesc& desc, MPI_Comm comm);

}  // namespace sortlast
