#include "service/request_translation.h"

#include <cmath>

#include "transfer/colormap_presets.h"
#include "common/error.h"
#include "scene/scene.h"

namespace sortlast {

namespace {

// Keys of the request itself, not of the scene.
bool isRequestField(const std::string& key) { return key == "id" || key == "format" || key == "quality"; }

bool isScenePrefix(const std::string& path) {
  // One entry of volumes ({"volumes[1]": {"transfer": {...}}}) and its transfer map: the path
  // with a key appended parses as that entry's key `visible` or `transfer.visible`.
  if (const auto field = parseFieldEntryKey(path + ".visible"))
    return field->key == "visible" || field->key == "transfer.visible";
  for (const SceneKey& k : sceneKeys())
    if (std::string(k.path).rfind(path + ".", 0) == 0) return true;
  return false;
}

void checkFinite(const std::string& key, const nlohmann::json& v) {
  if (v.is_number_float() && !std::isfinite(v.get<double>()))
    throw InputError("key '" + key + "': values must be finite numbers");
  if (v.is_array() || v.is_object())
    for (const auto& e : v) checkFinite(key, e);
}

// A request may pick a built-in colour map, not name a file: the service may face a network, and
// a client must not read the server's files (nor learn which exist from the error messages).
// Files belong in the scene the service started with.
void checkColourMap(const std::string& key, const nlohmann::json& v) {
  if (!v.is_string())
    throw InputError("key '" + key + "': expected the name of a built-in colour map, or \"\" for none");
  const std::string name = v.get<std::string>();
  if (name.empty() || isBuiltinColourMap(name)) return;
  std::string known;
  for (const std::string& n : builtinColourMapNames()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("key '" + key + "': a request may name a built-in colour map only (" + known +
                   ") or \"\" for none, not '" + name + "'; a colour-map file goes in the scene the service starts with");
}

void flatten(const std::string& prefix, const nlohmann::json& obj, std::vector<std::string>& out) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (prefix.empty() && isRequestField(key)) continue;
    // A nested map of scene keys ({"camera": {"fov": 30}}) is the same as its dotted names.
    if (it.value().is_object() && isScenePrefix(key)) {
      flatten(key, it.value(), out);
      continue;
    }
    checkFinite(key, it.value());
    // (one field's too: volumes[i].transfer.colormap)
    const auto field = parseFieldEntryKey(key);
    if (key == "transfer.colormap" || (field && field->key == "transfer.colormap")) checkColourMap(key, it.value());
    out.push_back(key + "=" + it.value().dump());
  }
}

}  // namespace

TranslatedRequest translateRequest(const nlohmann::json& body) {
  if (!body.is_object()) throw InputError("a frame request must be a JSON object of scene keys");
  TranslatedRequest t;
  flatten("", body, t.overrides);
  if (body.contains("format")) {
    if (!body["format"].is_string()) throw InputError("key 'format': expected \"png\" or \"jpeg\"");
    t.format = body["format"].get<std::string>();
    if (t.format == "jpg") t.format = "jpeg";
    if (t.format != "png" && t.format != "jpeg")
      throw InputError("key 'format': expected \"png\" or \"jpeg\", got \"" + t.format + "\"");
  }
  if (body.contains("quality")) {
    const auto& q = body["quality"];
    if (!q.is_number_integer() || q.get<long long>() < 1 || q.get<long long>() > 100)
      throw InputError("key 'quality': expected an integer in [1, 100]");
    t.quality = q.get<int>();
  }
  return t;
}

std::string packOverrides(const std::vector<std::string>& overrides) {
  return nlohmann::json(overrides).dump();
}

std::vector<std::string> unpackOverrides(const std::string& packed) {
  return nlohmann::json::parse(packed).get<std::vector<std::string>>();
}

}  // namespace sortlast
