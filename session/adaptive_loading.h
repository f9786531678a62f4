#pragma once
// Adaptive sampling in the render job (adaptive.tolerance > 0): the adaptive blocks each rank's
// ray caster draws.
//
// EVERY RANK READS THE WHOLE VOLUME in this mode. The preprocessing chooses levels on the block
// grid of the whole volume and stitches each block to its neighbours (adaptive/adaptive_blocks.h),
// so it cannot run on a rank's own bricks alone. Each rank reads everything and builds the same
// AdaptiveVolume (the build is deterministic: same input, same bits, whatever the thread count),
// so all ranks see one field without exchanging anything; each then keeps, per brick it owns,
// only the blocks that brick overlaps (adaptive/adaptive_brick.h). The price: reading the whole
// file on every rank, and while building each rank holds the whole volume as float, the
// pyramid (about 1/7 of it) and the whole atlas (AdaptiveSummary::stored_fraction of it), all
// released before the first frame; what stays is the bricks' own atlases. Ranks on one node
// split its cores for the build.
#include <mpi.h>

#include <vector>

#include "adaptive/adaptive_brick.h"
#include "common/brick.h"
#include "scene/scene.h"

namespace sortlast {

// Whether the scene renders its volume from adaptive blocks. Throws InputError (naming both
// keys) when it asks for them with a volume renderer that cannot draw them.
bool usesAdaptiveBlocks(const Scene& scene);

struct AdaptiveRankData {
  std::vector<AdaptiveBrickBlocks> bricks;  // per brick of `mine`, same order
  // Range of the original samples: the transfer function's, as without adaptive sampling.
  double data_min = 0, data_max = 0;
  // Slowest rank's seconds: reading the whole volume; building the adaptive volume (pyramid,
  // levels, stitching, atlas: what `sortlast adaptive-stats` times, here with cold memory);
  // cutting out the blocks of the rank's bricks.
  double read_s = 0, preprocess_s = 0, bricks_s = 0;
  double data_left = 0;  // dataLeft(): the paper's "data left", a fraction of the original
};

// Collective: every rank reads the whole volume (see above); a failure anywhere ends all ranks.
AdaptiveRankData loadAdaptiveBricks(const Scene& scene, const std::vector<Brick>& bricks,
                                    const std::vector<int>& mine, MPI_Comm comm);

}  // namespace sortlast
