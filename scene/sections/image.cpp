// The image section's keys: the image: size and background.
#include "scene/key_rows.h"

std::vector<sortlast::SceneKey> sortlast::imageKeys() {
  // Checked by parseScene with both sizes in the message.
  const Check kImageSize{"in [1, 32768]", nullptr};
  return {
    {"image.width", "512", "Image width in pixels.",
     Int{member<&Scene::camera, &Camera::width>, {kImageSize}}},
    {"image.height", "512", "Image height in pixels.",
     Int{member<&Scene::camera, &Camera::height>, {kImageSize}}},
    {"image.background", "[0, 0, 0]",
     "Colour the frame is composited over when written (premultiplied images stay exact).",
     Vector<glm::dvec3>{member<&Scene::image, &ImageSection::background>}},
  };
}
