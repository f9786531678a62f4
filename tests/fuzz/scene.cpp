// libFuzzer target: the scene parser (scene/scene.h) on a scene file's text plus `--set`
// overrides. Input: the YAML text, then each override after a NUL byte. Bad input must end in
// InputError (the message naming the key that main prints); any other exception escapes and
// libFuzzer reports it.
#include <cstdint>
#include <string>
#include <vector>

#include "common/error.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sortlast;
  std::string all(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> parts;
  for (size_t start = 0;;) {
    size_t nul = all.find('\0', start);
    parts.push_back(all.substr(start, nul - start));
    if (nul == std::string::npos) break;
    start = nul + 1;
  }
  // A path in a directory that does not exist: a relative file a scene names is not found.
  SceneText text{"/nonexistent-fuzz-dir/scene.yaml", parts[0]};
  std::vector<std::string> overrides(parts.begin() + 1, parts.end());
  try {
    Scene s = parseScene(text, overrides);
    (void)s;
  } catch (const InputError&) {
  }
  return 0;
}
