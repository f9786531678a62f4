// The limits section's keys: memory limits.
#include "scene/key_rows.h"

std::vector<sortlast::SceneKey> sortlast::limitKeys() {
  return {
    {"limits.memory_mib", "auto",
     "Memory a rank may use, MiB; scenes estimated to need more are refused before loading. "
     "`auto`: 90% of MemAvailable (/proc/meminfo), shared by the ranks on the node.",
     OptionalReal{member<&Scene::limits, &LimitsSection::memory_mib>,
                  {{"in (0, 1e12]", "must be auto or {allowed} MiB"}}},
     AutoValue{}},
  };
}
