#pragma once
// One time step's data on one rank, as a resident session holds it: its own bricks' samples (or
// their adaptive blocks), the data range and histogram over all ranks, and its particles with
// ghosts. StepCache keeps the last few steps within a memory bound so going back to a step reads
// nothing.
#include <mpi.h>

#include <list>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "session/adaptive_loading.h"
#include "session/fields_loading.h"
#include "session/particle_loading.h"
#include "session/session_layout.h"

namespace sortlast {

struct StepData {
  int step = -1;
  std::vector<std::vector<float>> samples;  // per brick of layout.mine (stored box); empty: adaptive
  AdaptiveRankData adaptive;                // adaptive sampling only
  std::vector<FieldStep> fields;            // several fields (`volumes`): each one's parts; samples empty
  bool has_volume = false;
  double data_min = 0, data_max = 0;        // over every rank
  // Rank 0: kHistogramBins bins even in histogram_scale (the scene's transfer.scale) over
  // [histogram_lo, histogram_hi]: the data's range, its low end the given transfer.range's under a
  // log scale over data through zero (samples <= 0 in bin 0); linear where log has no positive end.
  std::vector<long long> histogram;
  ValueScale histogram_scale;
  double histogram_lo = 0, histogram_hi = 0;
  LoadedParticles loaded;  // rank 0: the whole set, or (HDF5) each rank its share: to scatter anew
  std::vector<glm::vec3> particles;         // this rank's region's particles and ghosts
  double scattered_h = 0;                   // the ghost margin `particles` were chosen with
  double cost_mib = 0;                      // the largest any rank holds for this step
  // Rank 0: every rank's seconds reading its volume bricks (ghosts included) and its peak resident
  // memory just after (MiB): --stats' volume_read_s and peak_rss_after_read_mb (bench/io/run).
  std::vector<double> read_s, read_peak_rss_mb;
  std::string hdf5_transfers;  // an HDF5 volume: "collective" or "independent" (volume.mpi_io)
  bool dropped = false;                     // dropHostCopies() was called

  // Drops what the GPU holds now (a batch render needs no second copy).
  void dropHostCopies();
};

// Reads step `scene.time_step` (the scene's volume.file and particles.file are that step's).
// Collective; errors end the call on every rank (JobFailed).
// `preloaded`: the step's particle set, already loaded by rank 0 (the session reads the first
// step's set before the layout, which depends on its bounds).
StepData loadStep(const Scene& scene, const SessionLayout& layout, bool adaptive, MPI_Comm comm,
                  LoadedParticles* preloaded = nullptr);

// Sends every rank its particles again for a new influence radius h (from `loaded`, which
// dropHostCopies must not have dropped).
void scatterStepParticles(StepData& data, const SessionLayout& layout, double h, MPI_Comm comm);

// The recent steps, newest first, within `bound_mib` (the current step always stays). Every rank
// makes the same keep/evict decisions: a step's cost is the largest over ranks.
class StepCache {
 public:
  explicit StepCache(double bound_mib) : bound_mib_(bound_mib) {}
  // The step's data, loaded (collectively) unless cached.
  StepData& get(const Scene& scene, const SessionLayout& layout, bool adaptive, MPI_Comm comm);
  double heldMiB() const;
  // The next step loaded takes this particle set instead of reading its file.
  void preload(LoadedParticles set) { preloaded_ = std::move(set); has_preloaded_ = true; }
  size_t size() const { return steps_.size(); }

 private:
  double bound_mib_;
  std::list<StepData> steps_;
  LoadedParticles preloaded_;
  bool has_preloaded_ = false;
};

}  // namespace sortlast
