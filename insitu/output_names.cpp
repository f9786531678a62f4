#include "insitu/output_names.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "common/error.h"
#include "io/image.h"

namespace sortlast {

std::string stepLabel(long long step) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06lld", step);
  return buf;
}

std::string outputName(const std::string& pattern, long long step, int frame, int frames) {
  const std::string placeholder = kStepPlaceholder, label = stepLabel(step);
  std::string name = pattern;
  for (size_t at = name.find(placeholder); at != std::string::npos;
       at = name.find(placeholder, at + label.size()))
    name.replace(at, placeholder.size(), label);
  return frameFileName(name, frame, frames);
}

void createParentDirectories(const std::string& file) {
  std::filesystem::path parent = std::filesystem::path(file).parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) throw InputError("cannot create the folder " + parent.string() + ": " + ec.message());
}

}  // namespace sortlast
