#include "common/install_prefix.h"

namespace sortlast {

std::filesystem::path installPrefixOf(const std::filesystem::path& file, const std::string& subdir) {
  const std::filesystem::path sub(subdir);
  if (sub.is_absolute()) return {};
  std::filesystem::path prefix = file.parent_path();
  for (const auto& part : sub.lexically_normal()) {
    if (part.empty() || part == ".") continue;
    prefix = prefix.parent_path();
  }
  return prefix;
}

}  // namespace sortlast
