#include "scene/fields_scene.h"

#include <cctype>
#include <cmath>
#include <string_view>

namespace sortlast {

GridGeometry fieldsGrid(const std::vector<FieldSpec>& fields) {
  GridGeometry g;
  if (fields.empty()) return g;
  g.spacing = fields[0].volume.grid.spacing;
  glm::dvec3 half(0.0);
  for (const FieldSpec& f : fields) {
    g.spacing = glm::min(g.spacing, f.volume.grid.spacing);
    half = glm::max(half, 0.5 * glm::dvec3(f.volume.grid.dims - 1) * f.volume.grid.spacing);
  }
  // (dims - 1) spacing >= 2 half; the 1e-9 keeps a box that fits exactly from growing a cell.
  for (int a = 0; a < 3; ++a)
    g.dims[a] = int(std::ceil(2.0 * half[a] / g.spacing[a] - 1e-9)) + 1;
  return g;
}

}  // namespace sortlast

namespace sortlast {

std::string fieldMessage(const std::string& message, const std::string& name) {
  if (name == "volume") return message;
  std::string out;
  // A key, not prose: the word starts the message or follows a non-name character, and a key's
  // lower-case name follows the dot ("the volume. " stays).
  auto keyAt = [&](size_t i, std::string_view word) {
    const size_t n = word.size();
    return message.compare(i, n, word) == 0 && i + n < message.size() &&
           std::islower(static_cast<unsigned char>(message[i + n])) &&
           (i == 0 || !(std::isalnum(static_cast<unsigned char>(message[i - 1])) || message[i - 1] == '_'));
  };
  for (size_t i = 0; i < message.size();) {
    if (keyAt(i, "volume.")) {
      out += name + ".";
      i += 7;
    } else if (keyAt(i, "transfer.")) {
      out += name + ".transfer.";
      i += 9;
    } else {
      out += message[i++];
    }
  }
  return out;
}

}  // namespace sortlast
