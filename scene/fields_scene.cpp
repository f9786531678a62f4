#include "scene/fields_scene.h"

#include <cctype>
#include <cmath>
#include <string_view>

#include "scene/scene_keys.h"

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

TransferSpec FieldSpec::shownTransfer() const {
  TransferSpec t = transfer;
  if (!visible)
    for (TfPoint& p : t.points) p.a = 0.0;
  return t;
}

std::vector<std::string> FieldEntryKey::path() const {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t dot; (dot = key.find('.', start)) != std::string::npos; start = dot + 1)
    parts.push_back(key.substr(start, dot - start));
  parts.push_back(key.substr(start));
  return parts;
}

std::optional<FieldEntryKey> parseFieldEntryKey(const std::string& path) {
  const std::string_view prefix = "volumes[";
  if (!std::string_view(path).starts_with(prefix)) return std::nullopt;
  const size_t close = path.find("].", prefix.size());
  // 1-6 digits: an index, not a number that overflows
  if (close == std::string::npos || close == prefix.size() || close - prefix.size() > 6) return std::nullopt;
  size_t entry = 0;
  for (size_t i = prefix.size(); i < close; ++i) {
    if (!std::isdigit(static_cast<unsigned char>(path[i]))) return std::nullopt;
    entry = entry * 10 + size_t(path[i] - '0');
  }
  FieldEntryKey k{entry, path.substr(close + 2)};
  if (k.key.empty()) return std::nullopt;
  return k;
}

bool isFieldEntryKey(const std::string& key) {
  if (key == "visible") return true;
  if (key.starts_with("transfer.")) return findSceneKey(key) != nullptr;
  return key != "files" && findSceneKey("volume." + key) != nullptr;
}

bool isFieldFrameKey(const std::string& key) {
  return key == "visible" || (key.starts_with("transfer.") && findSceneKey(key) != nullptr);
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
