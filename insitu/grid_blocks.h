#pragma once
// The simulation's grid blocks as sortlast bricks: one brick per rank, made from the block the rank
// published, read where it lies. Each rank's brick spans the cells from its first owned sample up to
// the first sample of its upper neighbours (so the bricks tile the grid's cells, as sortlast's own
// bricks do), plus one ghost layer where the grid continues; the samples beyond its own it gets
// from its neighbours in one exchange of thin shells. The ghost layers a block carries are skipped
// (they only locate its owned samples), so blocks with and without them give the same bricks.
#include <mpi.h>

#include <memory>
#include <vector>

#include "common/brick.h"
#include "common/grid.h"
#include "sortlast/insitu.h"
#include "render/volume/brick_samples.h"

namespace sortlast {

struct GridLayout {
  GridGeometry grid;             // global dims and spacing; sortlast centres the grid on the origin
  glm::dvec3 shift{0.0};         // simulation world position of sortlast's origin
  std::vector<IndexBox> owned;   // per rank: its owned samples (global indices; empty: count 0)
  std::vector<Brick> bricks;     // per rank, id = rank; a rank without cells has an empty domain
  bool hasCells(int rank) const;
};

// Collective. Checks that the blocks tile one grid (same spacing, origins on the lattice, no
// overlap, no gap); throws InputError naming the rank and the problem.
GridLayout gatherGridLayout(const GridBlock& mine, MPI_Comm comm);

// Smallest and largest of this rank's owned samples; throws InputError at the first NaN or
// infinity, naming its global index. (float max, float lowest) when the rank owns nothing.
std::pair<double, double> ownedRange(const GridBlock& mine, const GridLayout& layout, int rank);

// This rank's stored samples: its own block where it lies, plus the shell fetched from its
// neighbours (collective: every rank sends what the others need).
class SimulationSamples : public BrickSamples {
 public:
  SimulationSamples(const GridBlock& mine, const GridLayout& layout, MPI_Comm comm);
  std::pair<float, float> range(const IndexBox& box) const override;
  void upload(const GlApi& gl, const IndexBox& stored) const override;
  // The samples of `stored` (this rank's brick's stored box) as float, x fastest: what upload()
  // sends, for the frame's accuracy estimate (session/frame_estimate.h), which reads the field on
  // the CPU. A copy: the brick's size in host memory while the estimate runs.
  std::vector<float> read(const IndexBox& stored) const;
  // Bytes this object holds beyond the simulation's arrays (the shell; the upload's chunk buffer).
  double bytesHeld() const;

 private:
  struct Piece {
    IndexBox box;
    std::vector<float> values;  // x fastest
  };
  GridBlock block_;
  IndexBox owned_;
  std::vector<Piece> shell_;
  mutable size_t chunk_bytes_ = 0;
};

}  // namespace sortlast
