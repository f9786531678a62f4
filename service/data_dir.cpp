#include "service/data_dir.h"

#include <algorithm>
#include <system_error>

#include "common/error.h"

namespace sortlast {

namespace fs = std::filesystem;

namespace {

// True when `p` is `root` or lies below it; both canonical, so a lexical comparison of whole
// components is exact ("/data2" is not inside "/data").
bool inside(const fs::path& root, const fs::path& p) {
  auto [r, q] = std::mismatch(root.begin(), root.end(), p.begin(), p.end());
  return r == root.end();
}

}  // namespace

namespace {

// dir/relative, canonical, checked to lie inside canonical(dir); it need not exist.
fs::path resolveInside(const fs::path& dir, const std::string& relative) {
  auto fail = [&](const std::string& why) { return InputError("\"" + relative + "\": " + why); };
  if (relative.empty()) throw InputError("empty file name");
  if (relative.find('\0') != std::string::npos) throw fail("the name holds a NUL character");
  fs::path rel(relative);
  if (rel.is_absolute() || rel.has_root_path())
    throw fail("absolute paths are not allowed, give a path relative to the directory");
  for (const auto& part : rel)
    if (part == "..") throw fail("\"..\" is not allowed in the path");

  std::error_code ec;
  fs::path root = fs::canonical(dir, ec);
  if (ec) throw InputError("directory " + dir.string() + ": " + ec.message());
  fs::path full = fs::weakly_canonical(root / rel, ec);
  if (ec) throw fail(ec.message());
  // Checked before existence, so a client cannot probe which files exist outside.
  if (!inside(root, full)) throw fail("leads outside the directory (through a symbolic link?)");
  return full;
}

}  // namespace

fs::path resolveUnder(const fs::path& dir, const std::string& relative) {
  fs::path full = resolveInside(dir, relative);
  std::error_code ec;
  if (!fs::exists(full, ec)) throw InputError("\"" + relative + "\": no such file");
  return full;
}

fs::path resolveNewUnder(const fs::path& dir, const std::string& relative) {
  fs::path full = resolveInside(dir, relative);
  auto fail = [&](const std::string& why) { return InputError("\"" + relative + "\": " + why); };
  std::error_code ec;
  if (full == fs::canonical(dir, ec)) throw fail("names the directory itself, not a file in it");
  if (!fs::is_directory(full.parent_path(), ec)) throw fail("its folder does not exist");
  if (fs::exists(full, ec) && !fs::is_regular_file(full, ec)) throw fail("exists and is not a file");
  return full;
}

std::vector<std::string> listSceneFiles(const fs::path& dir) {
  std::error_code ec;
  auto it =
      fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied, ec);
  if (ec) throw InputError("directory " + dir.string() + ": " + ec.message());
  std::vector<std::string> files;
  for (auto end = fs::recursive_directory_iterator(); it != end; it.increment(ec)) {
    if (ec) break;  // a folder vanished or became unreadable while listing: list what we have
    auto ext = it->path().extension();
    if (ext != ".yaml" && ext != ".yml") continue;
    if (!it->is_regular_file(ec)) continue;
    std::string rel = it->path().lexically_relative(dir).generic_string();
    try {
      resolveUnder(dir, rel);
      files.push_back(rel);
    } catch (const InputError&) {
      // A symlink leading out, say: not offered, since loading it would be refused.
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace sortlast
