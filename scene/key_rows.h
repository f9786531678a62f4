#pragma once
// What the section files (scene/sections/*.cpp) write their rows of the key table with: the key
// types by their short names, the checks several sections share, and one function per section
// that appends its rows. Only the section files and the table (scene_keys.cpp) include this.
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_keys.h"

namespace sortlast::key_rows {

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

}  // namespace sortlast::key_rows

namespace sortlast {

// Each section's rows, appended in the order of docs/scene.md (scene_keys.cpp calls them).
void addVolumeKeys(std::vector<SceneKey>& table);
void addParticleKeys(std::vector<SceneKey>& table);
void addTransferKeys(std::vector<SceneKey>& table);
void addImageKeys(std::vector<SceneKey>& table);
void addCameraKeys(std::vector<SceneKey>& table);
void addBrickKeys(std::vector<SceneKey>& table);
void addRenderKeys(std::vector<SceneKey>& table);
void addAdaptiveKeys(std::vector<SceneKey>& table);
void addCompositingKeys(std::vector<SceneKey>& table);
void addTimeKeys(std::vector<SceneKey>& table);
void addLimitKeys(std::vector<SceneKey>& table);
void addGlowKeys(std::vector<SceneKey>& table);
void addSurfaceKeys(std::vector<SceneKey>& table);
void addReferenceKeys(std::vector<SceneKey>& table);

}  // namespace sortlast
