#pragma once
// What the section files (scene/sections/*.cpp) write their rows of the key table with: the key
// types by their short names, the checks several sections share, and one function per section
// that appends its rows. Only the section files and the table (scene_keys.cpp) include this.
// One row per key: its path, its default (YAML), its help, its type (where the value goes and
// what it may be), and AutoValue where `auto` is one of its values (scene/scene_keys.h).
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_keys.h"

namespace sortlast {

using Real = Number<double>;
using OptionalReal = Number<std::optional<double>>;
using Int = Number<int>;
using Long = Number<long long>;

// A Choice of a text field whose names are its values.
inline std::vector<std::pair<const char*, std::string>> names(std::initializer_list<const char*> list) {
  std::vector<std::pair<const char*, std::string>> out;
  for (const char* n : list) out.emplace_back(n, n);
  return out;
}

// Float math on the GPU (common/box.h): the lengths it can hold, the coordinates it can square.
inline Check lengthCheck() {
  return {"in [1e-12, 1e18]", "{value} is outside {range}, the lengths float math on the GPU can hold"};
}
inline Check coordinateCheck() {
  return {"in [-1e18, 1e18]",
          "{value} is beyond +-1e18, which float math on the GPU cannot hold (it squares distances)"};
}
inline Check positiveCheck() { return {"a finite number > 0"}; }
inline Check colourCheck() { return {"in [0, 1]", "entries must be {allowed}"}; }


// Each section's rows (scene_keys.cpp puts them in the order of docs/scene.md).
std::vector<SceneKey> volumeKeys();
std::vector<SceneKey> particleKeys();
std::vector<SceneKey> transferKeys();
std::vector<SceneKey> volumesKeys();
std::vector<SceneKey> imageKeys();
std::vector<SceneKey> cameraKeys();
std::vector<SceneKey> clipKeys();
std::vector<SceneKey> brickKeys();
std::vector<SceneKey> renderKeys();
std::vector<SceneKey> adaptiveKeys();
std::vector<SceneKey> compositingKeys();
std::vector<SceneKey> timeKeys();
std::vector<SceneKey> limitKeys();
std::vector<SceneKey> glowKeys();
std::vector<SceneKey> surfaceKeys();
std::vector<SceneKey> referenceKeys();

}  // namespace sortlast
