// The time section's keys: time series: the step to render, the cache of steps.
// One row per key: its path, its default (YAML), its help, its type (where the value goes and what
// it may be), and AutoValue where `auto` is one of its values (scene/scene_keys.h).
#include "scene/key_rows.h"

namespace sortlast {

void addTimeKeys(std::vector<SceneKey>& table) {
  using namespace key_rows;
  table.insert(table.end(), {
    {"time.step", "0",
     "The time step to render, 0 ... steps - 1 (a scene with `volume.files`, "
     "`particles.files`, a 4-D NetCDF `volume.variable` or an HDF5 `volume.dataset` with "
     "`{step}`; otherwise only 0).",
     Int{member<&Scene::time, &TimeSection::step>}},
    {"time.cache_mib", "1024",
     "A resident session (`sortlast serve`) keeps the samples and particles of recent time steps "
     "in memory, up to this many MiB per rank, so going back to a step needs no reading.",
     Real{member<&Scene::time, &TimeSection::cache_mib>, {{"in [0, 1e9]", "must be {allowed} MiB"}}}},
  });
}

}  // namespace sortlast
