// The limits section's keys: memory limits.
// One row per key: its path, its default (YAML), its help, its type (where the value goes and what
// it may be), and AutoValue where `auto` is one of its values (scene/scene_keys.h).
#include "scene/key_rows.h"

namespace sortlast {

void addLimitKeys(std::vector<SceneKey>& table) {
  using namespace key_rows;
  table.insert(table.end(), {
    {"limits.memory_mib", "auto",
     "Memory a rank may use, MiB; scenes estimated to need more are refused before loading. "
     "`auto`: 90% of MemAvailable (/proc/meminfo), shared by the ranks on the node.",
     OptionalReal{member<&Scene::limits, &LimitsSection::memory_mib>,
                  {{"in (0, 1e12]", "must be auto or {allowed} MiB"}}},
     AutoValue{}},
  });
}

}  // namespace sortlast
