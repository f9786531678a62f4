#include "scene/file_steps.h"

#include <algorithm>
#include <string>

#include "common/build_features.h"
#include "common/error.h"
#include "common/missing_feature.h"

namespace sortlast {

namespace {

bool netcdfVolume(const Scene& s) {
  return !s.volume.file.empty() && s.time.volume_files.empty() &&
         s.volume.formatOf() == VolumeFormat::kNetcdf;
}

bool hdf5Series(const Scene& s) {
  return !s.volume.file.empty() && s.volume.dataset.find("{step}") != std::string::npos;
}

}  // namespace

bool hasFileSteps(const Scene& s) { return netcdfVolume(s) || hdf5Series(s); }

void resolveFileSteps(Scene& s) {
  if (!hasFileSteps(s)) return;
  VolumeDesc& vol = s.volume;
  const size_t particle_steps = s.time.particle_files.size();
  size_t records = 0;
  // The file's steps are read through its format's library: refused where the build has none.
  requireVolumeFormatBuilt(vol);
  if (!build::kHdf5 && hdf5Series(s)) refuseMissingFeature(Feature::kHdf5, "volume.dataset " + vol.dataset);
  if (netcdfVolume(s)) {
    VolumeDesc probe = vol;
    if constexpr (build::kNetcdf) describeNetcdf(probe);
    if (probe.records > 1) records = size_t(probe.records);
    if (records > 0 && particle_steps > 0 && particle_steps != records)
      throw InputError("volume.file " + vol.file + " holds " + std::to_string(records) +
                       " time steps (records of " + probe.variable + ") and particles.files names " +
                       std::to_string(particle_steps) + ": a series needs one of each per step");
  }
  const bool hdf5_series = hdf5Series(s);
  if (hdf5_series) {
    if constexpr (build::kHdf5) records = size_t(countHdf5Steps(vol));
    if (particle_steps > 0 && particle_steps != records)
      throw InputError("volume.file " + vol.file + " holds " + std::to_string(records) + " time steps (datasets " +
                       vol.dataset + ") and particles.files names " + std::to_string(particle_steps) +
                       ": a series needs one of each per step");
  }
  s.time.steps = int(std::max({size_t(1), particle_steps, records}));
  if (s.time.step < 0 || s.time.step >= s.time.steps)
    throw InputError("scene key 'time.step': " + std::to_string(s.time.step) + " is out of range: the scene has " +
                     std::to_string(s.time.steps) + " time step(s), 0 ... " + std::to_string(s.time.steps - 1));
  if (records > 0) vol.step = s.time.step;
  if constexpr (build::kHdf5)
    if (hdf5_series) vol.dataset = hdf5StepPath(vol.dataset, s.time.step);
  checkGlowRates(s.glow.emitters, s.time.steps * std::max(1, s.orbit.frames));
}

}  // namespace sortlast
