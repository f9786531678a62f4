// The time section's keys: time series: the step to render, the cache of steps.
#include "scene/key_rows.h"

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
