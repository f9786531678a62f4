#pragma once
// What the parser (scene.cpp) and the sections' rules (scene/sections/*.cpp) read a scene file with:
// typed values by key path with the table's defaults (Reader), where relative file names start
// (Origin), and each section's rules that a row cannot say (structured keys, `auto` values derived
// from other keys, rules between its keys), in the order parseScene applies them. Internal to
// scene/.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "common/error.h"
#include "scene/scene.h"

namespace sortlast {

inline std::vector<std::string> splitPath(const std::string& path) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t i = 0; i <= path.size(); ++i)
    if (i == path.size() || path[i] == '.') {
      parts.push_back(path.substr(start, i - start));
      start = i + 1;
    }
  return parts;
}

inline std::string where(const YAML::Node& n) {
  auto m = n.Mark();
  return m.line >= 0 ? " (line " + std::to_string(m.line + 1) + ")" : "";
}

// Reads typed values by key path, falling back to the table's default.
class Reader {
 public:
  explicit Reader(YAML::Node root) : root_(std::move(root)) {}

  YAML::Node get(const std::string& path) const {
    YAML::Node n = YAML::Clone(root_);
    for (const std::string& p : splitPath(path)) {
      if (!n.IsMap() || !n[p]) return YAML::Load(sceneKey(path).default_yaml);
      n.reset(n[p]);
    }
    return n;
  }
  bool isAuto(const std::string& path) const {
    YAML::Node n = get(path);
    return n.IsNull() || (n.IsScalar() && n.Scalar() == "auto");
  }
  template <class T>
  T as(const std::string& path) const {
    YAML::Node n = get(path);
    try {
      if (!n.IsScalar()) throw YAML::Exception(n.Mark(), "not a scalar");
      return n.as<T>();
    } catch (const YAML::Exception&) {
      throw InputError("scene key '" + path + "': expected " + typeName<T>() + where(n));
    }
  }
  std::vector<double> numbers(const std::string& path, size_t n_expected) const {
    YAML::Node n = get(path);
    std::vector<double> v;
    try {
      if (!n.IsSequence()) throw YAML::Exception(n.Mark(), "not a list");
      for (const auto& e : n) v.push_back(e.as<double>());
    } catch (const YAML::Exception&) {
      v.clear();
    }
    if (v.size() != n_expected)
      throw InputError("scene key '" + path + "': expected a list of " + std::to_string(n_expected) +
                       " numbers" + where(n));
    for (double x : v)
      if (!std::isfinite(x)) throw InputError("scene key '" + path + "': values must be finite" + where(n));
    return v;
  }
  glm::dvec3 vec3(const std::string& path) const {
    auto v = numbers(path, 3);
    return {v[0], v[1], v[2]};
  }

 private:
  template <class T>
  static std::string typeName() {
    if constexpr (std::is_same_v<T, bool>) return "true or false";
    if constexpr (std::is_integral_v<T>) return "an integer";
    if constexpr (std::is_same_v<T, double>) return "a number";
    return "a string";
  }
  YAML::Node root_;
};

inline std::string numText(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// Where a relative file name starts: at the scene file, or for a key given with --set where the
// user runs (the name stays as given).
struct Origin {
  std::filesystem::path base_dir;
  std::set<std::string> overridden;  // keys given with --set

  bool fromOverride(const std::string& key) const { return overridden.count(key) > 0; }
  std::string resolve(const std::string& key, const std::string& file) const {
    const bool as_given = file.empty() || !std::filesystem::path(file).is_relative() || fromOverride(key);
    return as_given ? file : (base_dir / file).string();
  }
};

// A number that a section's own code read, by the table's checks of `key` (named `name` in the
// message).
void requireTable(const std::string& key, double v, const std::string& name);

// Reads the keys the table types (scene.cpp), only those under `prefixes` if any are given.
void readTypedKeys(const Reader& r, const Origin& o, Scene& s, const std::vector<std::string>& prefixes = {});

// The sections' rules, each in its section's file.
void checkVolumeKeys(const Scene& s);                                       // sections/volume.cpp
void checkParticleKeys(const Reader& r, ParticleDesc& p);                   // sections/particles.cpp
std::vector<std::string> readSeries(const Reader& r, const std::string& key, const Origin& o);  // time.cpp
void checkTimeKeys(Scene& s);                                               // sections/time.cpp
void readGlowKeys(const Reader& r, Scene& s);                               // sections/glow.cpp
// render.blend's projections against the rest of the scene (scene/projection_rules.cpp).
void checkProjectionKeys(const Scene& s);
void checkRenderKeys(const Scene& s);                                       // sections/render.cpp
void readTransferKeys(const Reader& r, const Origin& o, TransferSpec& tf);  // sections/transfer.cpp
void checkCameraKeys(const Scene& s);                                       // sections/camera.cpp
void readClipKeys(const Reader& r, Scene& s);                               // sections/clip.cpp
// `volumes`: the fields (`root`: the scene as given, to tell whether it sets volume.* too).
// Returns whether the first field's transfer.preintegrated is auto; nullopt without `volumes`.
std::optional<bool> readVolumesKey(const Reader& r, const Origin& o, const YAML::Node& root, Scene& s);  // sections/volumes.cpp

}  // namespace sortlast
