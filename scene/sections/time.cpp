// The time section's keys: time series: the step to render, the cache of steps.
#include "scene/key_rows.h"
#include "scene/scene_reader.h"
#include <glob.h>
#include <algorithm>
#include "scene/file_steps.h"

std::vector<sortlast::SceneKey> sortlast::timeKeys() {
  return {
    {"time.step", "0",
     "The time step to render, 0 ... steps - 1 (a scene with `volume.files`, "
     "`particles.files`, a 4-D NetCDF `volume.variable` or an HDF5 `volume.dataset` with "
     "`{step}`; otherwise only 0).",
     Int{member<&Scene::time, &TimeSection::step>}},
    {"time.cache_mib", "1024",
     "A resident session (`sortlast serve`) keeps the samples and particles of recent time steps "
     "in memory, up to this many MiB per rank, so going back to a step needs no reading.",
     Real{member<&Scene::time, &TimeSection::cache_mib>, {{"in [0, 1e9]", "must be {allowed} MiB"}}}},
  };
}

namespace sortlast {

// volume.files / particles.files: a list of files, or one glob pattern (sorted matches).
std::vector<std::string> readSeries(const Reader& r, const std::string& key, const Origin& o) {
  YAML::Node n = r.get(key);
  auto resolve = [&](const std::string& f) { return o.resolve(key, f); };
  std::vector<std::string> files;
  if (n.IsNull() || (n.IsScalar() && n.Scalar().empty())) return files;
  if (n.IsSequence()) {
    for (const auto& e : n) {
      if (!e.IsScalar() || e.Scalar().empty())
        throw InputError("scene key '" + key + "': expected a list of file names" + where(e));
      files.push_back(resolve(e.Scalar()));
    }
    if (files.empty()) throw InputError("scene key '" + key + "': the list is empty" + where(n));
    return files;
  }
  if (!n.IsScalar()) throw InputError("scene key '" + key + "': expected a glob pattern or a list of files" + where(n));
  std::string pattern = resolve(n.Scalar());
  glob_t g{};
  int rc = glob(pattern.c_str(), GLOB_ERR, nullptr, &g);
  for (size_t i = 0; rc == 0 && i < g.gl_pathc; ++i) files.push_back(g.gl_pathv[i]);
  globfree(&g);
  if (files.empty()) throw InputError("scene key '" + key + "': no file matches '" + pattern + "'");
  std::sort(files.begin(), files.end());
  return files;
}

// The series' rules (volume.files, particles.files), the steps they give and time.step, and each
// series' file of this step. (Steps inside one file are resolveFileSteps', scene/file_steps.h.)
void checkTimeKeys(Scene& s) {
  VolumeDesc& vol = s.volume;
  if (!s.time.volume_files.empty() && !vol.file.empty())
    throw InputError("scene keys 'volume.file' and 'volume.files' are both set: use one");
  if (!s.time.particle_files.empty() && (!s.particles.file.empty() || s.particles.procedural != "none"))
    throw InputError("scene key 'particles.files' is set with 'particles.file' or "
                     "'particles.procedural': use one");
  if (!s.time.volume_files.empty() && !s.time.particle_files.empty() &&
      s.time.volume_files.size() != s.time.particle_files.size())
    throw InputError("scene keys 'volume.files' and 'particles.files' name " +
                     std::to_string(s.time.volume_files.size()) + " and " +
                     std::to_string(s.time.particle_files.size()) + " steps: a series needs one of each per step");
  // Steps inside one file (the records of a 4-D NetCDF variable, an HDF5 volume.dataset with
  // {step}) are the file's to say: parsing reads no data file, so those are counted, and time.step
  // checked against them, by resolveFileSteps (scene/file_steps.h) when the scene is loaded. What
  // needs no file is checked here.
  const bool hdf5_series = vol.dataset.find("{step}") != std::string::npos;
  if (hdf5_series && !s.time.volume_files.empty())
    throw InputError("volume.dataset " + vol.dataset + ": {step} makes one file a time series; with "
                     "volume.files (one file per step) name the dataset without {step}");
  if (hdf5_series && !vol.file.empty() && vol.formatOf() != VolumeFormat::kHdf5)
    throw InputError("volume.dataset " + vol.dataset + ": {step} needs an HDF5 volume.file, not " + vol.file);
  s.time.steps = int(std::max({size_t(1), s.time.volume_files.size(), s.time.particle_files.size()}));
  // (With a particle series beside a file's steps, the two must agree: its length bounds the step.)
  const bool steps_known = !hasFileSteps(s) || !s.time.particle_files.empty();
  if (s.time.step < 0 || (steps_known && s.time.step >= s.time.steps))
    throw InputError("scene key 'time.step': " + std::to_string(s.time.step) + " is out of range: the scene has " +
                     std::to_string(s.time.steps) + " time step(s), 0 ... " + std::to_string(s.time.steps - 1));
  if (!s.time.volume_files.empty()) vol.file = s.time.volume_files[size_t(s.time.step)];
  if (!s.time.particle_files.empty()) s.particles.file = s.time.particle_files[size_t(s.time.step)];
}

}  // namespace sortlast
