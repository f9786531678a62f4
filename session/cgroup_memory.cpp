#include "session/cgroup_memory.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace sortlast {

namespace {

namespace fs = std::filesystem;

std::string readAll(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(line);
  while (std::getline(in, part, sep)) parts.push_back(part);
  if (!line.empty() && line.back() == sep) parts.emplace_back();
  return parts;
}

// v1 writes "no limit" as the largest page-aligned long (9223372036854771712).
constexpr double kNoLimitV1 = 4.611686018427388e18;  // 2^62

// The limit in `file`: nullopt where it is absent, unreadable, "max" or v1's "none".
std::optional<double> limitIn(const fs::path& file, bool v1) {
  std::ifstream in(file);
  std::string text;
  if (!(in >> text) || text == "max") return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !(v > 0) || (v1 && v >= kNoLimitV1)) return std::nullopt;
  return v;
}

// The cgroup's folder under the mount: its path less the mount's root, and the folders above it
// up to the mount point, each holding its own limit.
std::optional<CgroupLimit> tightestOnPath(const std::string& mount, const std::string& mount_root,
                                          std::string path, const char* name, bool v1) {
  if (mount.empty()) return std::nullopt;
  if (mount_root != "/" && path.rfind(mount_root, 0) == 0) path = path.substr(mount_root.size());
  fs::path top = fs::path(mount).lexically_normal();
  if (!top.has_filename() && top.has_relative_path()) top = top.parent_path();  // "DIR/"
  fs::path dir = (top / fs::path(path).relative_path()).lexically_normal();
  if (!dir.has_filename() && dir.has_relative_path()) dir = dir.parent_path();
  // A path outside the mount ("/../x": the process's cgroup lies outside a namespace's root)
  // leaves only the mount's own limit to read.
  const std::string rel = dir.lexically_relative(top).string();
  if (rel.empty() || rel.rfind("..", 0) == 0) dir = top;
  std::optional<CgroupLimit> best;
  for (;; dir = dir.parent_path()) {
    if (auto v = limitIn(dir / name, v1); v && (!best || *v < best->bytes))
      best = CgroupLimit{*v, (dir / name).string()};
    if (dir == top || dir == dir.parent_path()) break;
  }
  return best;
}

}  // namespace

CgroupMounts cgroupMounts(const std::string& mountinfo) {
  // "ID PARENT MAJ:MIN ROOT MOUNTPOINT OPTIONS [OPTIONAL...] - FSTYPE SOURCE SUPEROPTIONS"
  CgroupMounts m;
  std::istringstream in(mountinfo);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> f = split(line, ' ');
    size_t dash = 0;
    while (dash < f.size() && f[dash] != "-") ++dash;
    if (f.size() < 5 || dash + 1 >= f.size()) continue;
    const std::string& type = f[dash + 1];
    const std::string super = dash + 3 < f.size() ? f[dash + 3] : "";
    if (type == "cgroup2" && m.v2.empty()) {
      m.v2 = f[4];
      m.v2_root = f[3];
    } else if (type == "cgroup" && m.v1_memory.empty()) {
      for (const std::string& o : split(super, ','))
        if (o == "memory") {
          m.v1_memory = f[4];
          m.v1_memory_root = f[3];
        }
    }
  }
  return m;
}

std::optional<CgroupLimit> cgroupMemoryLimit(const std::string& proc_self_cgroup,
                                             const CgroupMounts& mounts) {
  std::string v2_path, v1_path;
  bool has_v2 = false, has_v1 = false;
  std::istringstream in(proc_self_cgroup);
  for (std::string line; std::getline(in, line);) {
    // "HIERARCHY-ID:CONTROLLERS:PATH" (the path may itself hold ':')
    const size_t a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    const std::string id = line.substr(0, a), controllers = line.substr(a + 1, b - a - 1);
    const std::string path = line.substr(b + 1);
    if (id == "0" && controllers.empty()) {
      v2_path = path;
      has_v2 = true;
    }
    for (const std::string& c : split(controllers, ','))
      if (c == "memory") {
        v1_path = path;
        has_v1 = true;
      }
  }
  // v2 first; v1 where no v2 limit applies (a hybrid system keeps its memory controller on v1).
  if (has_v2)
    if (auto l = tightestOnPath(mounts.v2, mounts.v2_root, v2_path, "memory.max", false)) return l;
  if (has_v1)
    return tightestOnPath(mounts.v1_memory, mounts.v1_memory_root, v1_path, "memory.limit_in_bytes", true);
  return std::nullopt;
}

std::optional<CgroupLimit> processCgroupMemoryLimit() {
  CgroupMounts mounts;
  if (const char* root = std::getenv("SORTLAST_CGROUP_ROOT"); root && *root) {
    mounts.v2 = root;
    mounts.v1_memory = (fs::path(root) / "memory").string();
  } else {
    mounts = cgroupMounts(readAll("/proc/self/mountinfo"));
  }
  return cgroupMemoryLimit(readAll("/proc/self/cgroup"), mounts);
}

}  // namespace sortlast
