// The bricks section's keys: the cut of the scene into bricks.
#include "scene/key_rows.h"

std::vector<sortlast::SceneKey> sortlast::brickKeys() {
  return {
    {"bricks.per_axis", "auto",
     "d: the scene is cut into d x d x d bricks. `auto`: 2, but 1 for a scene of glow emitters "
     "alone (their integral splits anywhere, so one brick draws them in one pass; docs/glow.md).",
     Int{member<&Scene::bricks, &BricksSection::per_axis>, {{"in [1, 64]"}}}, AutoValue{}},
  };
}
