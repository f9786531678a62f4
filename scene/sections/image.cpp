// The image section's keys: the image: size and background.
// One row per key: its path, its default (YAML), its help, its type (where the value goes and what
// it may be), and AutoValue where `auto` is one of its values (scene/scene_keys.h).
#include "scene/key_rows.h"

namespace sortlast {

void addImageKeys(std::vector<SceneKey>& table) {
  using namespace key_rows;
  // Checked by parseScene with both sizes in the message.
  const Check kImageSize{"in [1, 32768]", nullptr};
  table.insert(table.end(), {
    {"image.width", "512", "Image width in pixels.",
     Int{member<&Scene::camera, &Camera::width>, {kImageSize}}},
    {"image.height", "512", "Image height in pixels.",
     Int{member<&Scene::camera, &Camera::height>, {kImageSize}}},
    {"image.background", "[0, 0, 0]",
     "Colour the frame is composited over when written (premultiplied images stay exact).",
     Vector<glm::dvec3>{member<&Scene::image, &ImageSection::background>}},
  });
}

}  // namespace sortlast
