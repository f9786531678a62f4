// The bricks section's keys: the cut of the scene into bricks.
// One row per key: its path, its default (YAML), its help, its type (where the value goes and what
// it may be), and AutoValue where `auto` is one of its values (scene/scene_keys.h).
#include "scene/key_rows.h"

namespace sortlast {

void addBrickKeys(std::vector<SceneKey>& table) {
  using namespace key_rows;
  table.insert(table.end(), {
    {"bricks.per_axis", "auto",
     "d: the scene is cut into d x d x d bricks. `auto`: 2, but 1 for a scene of glow emitters "
     "alone (their integral splits anywhere, so one brick draws them in one pass; docs/glow.md).",
     Int{member<&Scene::bricks, &BricksSection::per_axis>, {{"in [1, 64]"}}}, AutoValue{}},
  });
}

}  // namespace sortlast
