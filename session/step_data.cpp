#include "session/step_data.h"

#include <algorithm>
#include <cmath>

#include "session/collective.h"
#include "session/frame_stats.h"  // peakRssMiB
#include "common/build_features.h"
#include "session/hdf5_loading.h"
#include "session/volume_loading.h"

namespace sortlast {

namespace {

// Counts each grid sample once over all ranks: a brick counts the samples of its domain except
// those on an upper face that the next brick shares.
void addToHistogram(const Brick& b, const glm::ivec3& dims, const std::vector<float>& stored,
                    const HistogramBinner& binner, std::vector<long long>& bins) {
  const glm::ivec3 s = b.stored.size();
  for (int z = b.domain.lo.z; z <= b.domain.hi.z; ++z) {
    if (z == b.domain.hi.z && z != dims.z - 1) continue;
    for (int y = b.domain.lo.y; y <= b.domain.hi.y; ++y) {
      if (y == b.domain.hi.y && y != dims.y - 1) continue;
      for (int x = b.domain.lo.x; x <= b.domain.hi.x; ++x) {
        if (x == b.domain.hi.x && x != dims.x - 1) continue;
        glm::ivec3 i = glm::ivec3(x, y, z) - b.stored.lo;
        const int bin = binner.binOf(stored[(size_t(i.z) * s.y + i.y) * s.x + i.x]);
        if (bin >= 0) ++bins[size_t(bin)];  // (NaN: a missing sample)
      }
    }
  }
}

std::vector<Box3> rankRegions(const SessionLayout& layout, int size) {
  std::vector<Box3> regions;
  for (int r = 0; r < size; ++r) regions.push_back(cellRangeBox(layout.planes, layout.assignment.region[size_t(r)]));
  return regions;
}

}  // namespace

void StepData::dropHostCopies() {
  for (auto& s : samples) std::vector<float>().swap(s);
  for (auto& b : adaptive.bricks) b = {};
  for (auto& f : fields)
    for (auto& s : f.samples) std::vector<float>().swap(s);
  loaded.set = {};
  std::vector<glm::vec3>().swap(particles);
  dropped = true;
}

StepData loadStep(const Scene& scene, const SessionLayout& layout, bool adaptive, MPI_Comm comm,
                  LoadedParticles* preloaded) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  StepData d;
  d.step = scene.time.step;
  d.has_volume = scene.hasVolume();
  if (scene.hasFields()) {
    // Several fields: each one's parts of this rank's bricks, range and histogram
    // (session/fields_loading.h); the first field's range and histogram stand for the step's.
    std::vector<FieldSpec> fields = scene.fields;
    collectively(comm, [&] { validateFields(fields); });
    d.fields = loadFields(fields, layout, comm);
    d.data_min = d.fields[0].data_min, d.data_max = d.fields[0].data_max;
    const ValueHistogram& h = d.fields[0].histogram;
    d.histogram = h.counts, d.histogram_scale = h.scale, d.histogram_lo = h.lo, d.histogram_hi = h.hi;
  } else if (scene.hasVolume()) {
    // Every step of a series must have the layout's grid (a VTK file brings its own).
    Scene step_scene = scene;
    VolumeDesc& desc = step_scene.volume;
    collectively(comm, [&] {
      validateVolume(desc);
      const GridGeometry& g = layout.grid;
      if (desc.grid.dims != g.dims || desc.grid.spacing != g.spacing)
        throw InputError("volume file " + desc.file + " (time step " + std::to_string(d.step) +
                         ") has another grid than the session's first step: every step of "
                         "volume.files needs the same dims and spacing");
    });
    if (adaptive) {
      d.adaptive = loadAdaptiveBricks(step_scene, layout.volume_bricks, layout.mine, comm);
      d.data_min = d.adaptive.data_min, d.data_max = d.adaptive.data_max;
    } else {
      const double t0 = MPI_Wtime();
      d.samples = loadOwnBricks(desc, layout.volume_bricks, layout.mine, layout.assignment, comm);
      const double mine_s[2] = {MPI_Wtime() - t0, peakRssMiB()};
      if constexpr (build::kHdf5) {
        if (desc.formatOf() == VolumeFormat::kHdf5)
          d.hdf5_transfers = hdf5ReadsCollectively(desc, comm) ? "collective" : "independent";
      }
      std::vector<double> all(rank == 0 ? 2 * size_t(size) : 0);
      MPI_Gather(mine_s, 2, MPI_DOUBLE, all.data(), 2, MPI_DOUBLE, 0, comm);
      for (size_t r = 0; r < all.size() / 2; ++r) {
        d.read_s.push_back(all[2 * r]);
        d.read_peak_rss_mb.push_back(all[2 * r + 1]);
      }
      std::vector<long long> mine(kHistogramBins, 0);
      collectively(comm, [&] {  // every rank reaches the range's Allreduce, then throws or not
        std::tie(d.data_min, d.data_max) = globalRange(d.samples, desc.file, comm);
        // The histogram is even in the scene's transfer.scale (the viewer's editor is).
        const ValueHistogram h = ValueHistogram::framing(scene.transfer, d.data_min, d.data_max);
        d.histogram_scale = h.scale, d.histogram_lo = h.lo, d.histogram_hi = h.hi;
        const HistogramBinner binner(h);
        for (size_t i = 0; i < layout.mine.size(); ++i)
          addToHistogram(layout.volume_bricks[size_t(layout.mine[i])], desc.grid.dims,
                         d.samples[i], binner, mine);
      });
      d.histogram.assign(kHistogramBins, 0);
      MPI_Reduce(mine.data(), d.histogram.data(), kHistogramBins, MPI_LONG_LONG, MPI_SUM, 0, comm);
      if (rank != 0) d.histogram.clear();
    }
  }
  if (scene.particles.enabled()) {
    d.loaded = preloaded ? std::move(*preloaded) : loadParticleSet(scene.particles, comm);
    scatterStepParticles(d, layout, scene.particles.ghostMargin(), comm);
  }
  double mib = 0;
  for (const auto& s : d.samples) mib += double(s.size()) * sizeof(float);
  for (const auto& b : d.adaptive.bricks) mib += double(b.atlas.size()) * sizeof(float);
  for (const auto& f : d.fields)
    for (const auto& s : f.samples) mib += double(s.size()) * sizeof(float);
  mib += double(d.particles.size() + d.loaded.set.positions.size()) * sizeof(glm::vec3);
  mib /= 1024.0 * 1024.0;
  MPI_Allreduce(&mib, &d.cost_mib, 1, MPI_DOUBLE, MPI_MAX, comm);
  return d;
}

void scatterStepParticles(StepData& d, const SessionLayout& layout, double h, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  d.particles = scatterParticles(d.loaded, rankRegions(layout, size), h, comm);
  d.scattered_h = h;
}

StepData& StepCache::get(const Scene& scene, const SessionLayout& layout, bool adaptive, MPI_Comm comm) {
  auto it = std::find_if(steps_.begin(), steps_.end(), [&](const StepData& d) { return d.step == scene.time.step; });
  if (it != steps_.end()) {
    steps_.splice(steps_.begin(), steps_, it);  // newest first
    return steps_.front();
  }
  steps_.push_front(loadStep(scene, layout, adaptive, comm, has_preloaded_ ? &preloaded_ : nullptr));
  has_preloaded_ = false;
  // Evict the oldest beyond the bound; costs are the same on every rank, so are the decisions.
  double held = 0;
  for (auto s = steps_.begin(); s != steps_.end();) {
    held += s->cost_mib;
    if (s != steps_.begin() && held > bound_mib_) {
      held -= s->cost_mib;
      s = steps_.erase(s);
    } else {
      ++s;
    }
  }
  return steps_.front();
}

double StepCache::heldMiB() const {
  double held = 0;
  for (const auto& s : steps_) held += s.cost_mib;
  return held;
}

}  // namespace sortlast
