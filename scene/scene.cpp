#include "scene/scene.h"
#include "scene/isosurface_scene.h"
#include "scene/scene_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "common/error.h"

namespace sortlast {

namespace {

bool isMapPrefix(const std::string& path) {
  for (const SceneKey& k : sceneKeys())
    if (std::string(k.path).rfind(path + ".", 0) == 0) return true;
  return false;
}

// Every key in the file must be one we know: a typo must not silently fall back to a default.
void checkKeys(const YAML::Node& map, const std::string& prefix) {
  for (auto it = map.begin(); it != map.end(); ++it) {
    // A complex key (`? [a, b]`, `{a: 1}: x`) has no name: as<std::string>() would throw yaml-cpp's
    // bare "bad conversion" (found by tests/fuzz/scene).
    if (!it->first.IsScalar())
      throw InputError("scene file: a key " + std::string(prefix.empty() ? "" : "under '" + prefix + "' ") +
                       "is a list or map, not a name" + where(it->first));
    std::string name = it->first.as<std::string>();
    std::string full = prefix.empty() ? name : prefix + "." + name;
    if (findSceneKey(full)) continue;
    if (isMapPrefix(full)) {
      if (!it->second.IsMap()) throw InputError("scene key '" + full + "' must be a map" + where(it->second));
      checkKeys(it->second, full);
      continue;
    }
    throw InputError("unknown scene key '" + full + "'" + where(it->first) +
                     " (see docs/scene.md or `sortlast keys` for the known keys)");
  }
}

void setPath(YAML::Node node, const std::vector<std::string>& parts, size_t i, const YAML::Node& v) {
  if (i + 1 == parts.size()) {
    node[parts[i]] = v;
    return;
  }
  if (!node[parts[i]] || !node[parts[i]].IsMap()) node[parts[i]] = YAML::Node(YAML::NodeType::Map);
  setPath(node[parts[i]], parts, i + 1, v);
}

// `volumes[i].key=value` (scene/fields_scene.h): into entry i of the list the scene gives, which
// must exist and be a map; the entry's reading checks the key and value (readVolumesKey).
void setFieldEntryKey(YAML::Node root, const FieldEntryKey& field, const std::string& key, const YAML::Node& v) {
  if (!isFieldEntryKey(field.key))
    throw InputError("unknown scene key '" + key + "' (an entry of volumes takes the volume.* keys "
                     "without `volume.`, `visible` and `transfer.` with a transfer.* key: docs/scene.md)");
  YAML::Node list = root["volumes"];
  const size_t n = list.IsSequence() ? list.size() : 0;
  if (field.entry >= n)
    throw InputError("scene key '" + key + "': the scene's volumes list has " + std::to_string(n) +
                     (n == 1 ? " entry" : " entries") + (n ? " (volumes[0] to volumes[" + std::to_string(n - 1) + "])" : ""));
  YAML::Node entry = list[field.entry];
  if (!entry.IsMap())
    throw InputError("scene key '" + key + "': volumes[" + std::to_string(field.entry) + "] is not a map of keys");
  const std::vector<std::string> parts = field.path();
  if (parts.size() == 2 && entry[parts[0]].IsDefined() && !entry[parts[0]].IsMap())
    throw InputError("scene key '" + key + "': volumes[" + std::to_string(field.entry) + "]." + parts[0] + " is not a map");
  setPath(entry, parts, 0, v);
}

// A value as range errors show it: numbers as %g, integers in full.
template <class V>
std::string valueText(V v) {
  if constexpr (std::is_integral_v<V>) return std::to_string(v);
  else return numText(v);
}

// One of the table's checks; `r` gives the value as written, for a message that shows it.
void require(const Check& c, const std::string& key, double v, const std::string& value,
             const Reader* r = nullptr) {
  if (c.says && !c.allowed.admits(v)) {
    YAML::Node n = r ? r->get(key) : YAML::Node();
    throw InputError(c.error(key, value, n.IsScalar() ? n.Scalar() : ""));
  }
}

// Reading one key through its row (scene/scene_keys.h): its value, its checks, its field.
template <class T>
struct ValueOf {
  using type = T;
};
template <class T>
struct ValueOf<std::optional<T>> {
  using type = T;
};

template <class T>
void read(const Number<T>& n, const std::string& key, const Reader& r, const Origin&, Scene& s) {
  const auto v = r.as<typename ValueOf<T>::type>(key);
  for (const Check& c : n.checks) require(c, key, double(v), valueText(v), &r);
  n.field(s) = v;
}

void read(const Flag& f, const std::string& key, const Reader& r, const Origin&, Scene& s) {
  f.field(s) = r.as<bool>(key);
}

void read(const Text& t, const std::string& key, const Reader& r, const Origin& o, Scene& s) {
  const std::string v = r.as<std::string>(key);
  t.field(s) = t.file ? o.resolve(key, v) : v;
}

void read(const Choice& c, const std::string& key, const Reader& r, const Origin&, Scene& s) {
  const std::string name = r.as<std::string>(key);
  for (size_t i = 0; i < c.names.size(); ++i)
    if (name == c.names[i]) return c.set(s, i);
  throw InputError(choiceError(key, c.says, c.names, name));
}

template <class T>
void read(const Vector<T>& vec, const std::string& key, const Reader& r, const Origin&, Scene& s) {
  const glm::dvec3 v = r.vec3(key);
  for (const Check& c : vec.checks) {
    if (c.of_length) require(c, key, glm::length(v), numText(glm::length(v)));
    else
      for (int a = 0; a < 3; ++a) require(c, key, v[a], numText(v[a]));
  }
  vec.field(s) = T(v);
}

void read(const Structured&, const std::string&, const Reader&, const Origin&, Scene&) {}

}  // namespace

// Every key the table types, in the table's order: its value (`auto` leaves the field to its
// default or to parseScene), checked, into its field. With `prefixes`, only the keys under them.
void readTypedKeys(const Reader& r, const Origin& o, Scene& s, const std::vector<std::string>& prefixes) {
  for (const SceneKey& k : sceneKeys()) {
    if (!prefixes.empty() &&
        std::none_of(prefixes.begin(), prefixes.end(),
                     [&](const std::string& p) { return std::string_view(k.path).starts_with(p); }))
      continue;
    if (k.auto_value) {
      const bool is_auto = r.isAuto(k.path);
      if (k.auto_value->flag) k.auto_value->flag(s) = is_auto;
      if (is_auto) continue;
    }
    std::visit([&](const auto& type) { read(type, k.path, r, o, s); }, k.type);
  }
}

SceneText readSceneText(const std::string& path) {
  if (path.empty()) return {};
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("scene file " + path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError("scene file " + path + ": cannot read");
  return {path, text.str()};
}

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides) {
  return parseScene(readSceneText(path), overrides);
}

bool isFrameKey(const std::string& path) {
  // One field's transfer map and visibility (volumes[i].transfer.*, volumes[i].visible).
  if (const auto field = parseFieldEntryKey(path)) return isFieldFrameKey(field->key);
  for (const char* prefix : {"camera.", "clip.", "image.", "transfer.", "compositing.", "time.step"})
    if (path.rfind(prefix, 0) == 0) return true;
  for (const char* key : {"render.sample_spacing", "render.method", "render.ert_threshold",
                          "render.shading", "render.shading_ambient", "render.shading_diffuse",
                          "render.shading_specular", "render.shading_shininess",
                          "render.adaptive_step", "render.adaptive_tolerance", "render.pipeline",
                          "render.blend", "render.mip_exact", "render.isovalues",
                          "render.estimate", "render.estimate_pixels", "render.target_db",
                          "particles.radius", "particles.influence", "particles.threshold",
                          "particles.color", "particles.step", "particles.max_samples",
                          "particles.refine_iterations", "particles.cull", "particles.samples_per_pass",
                          // Emitters are uploaded every frame; a session refuses turning glow on or
                          // off (its bricks cover glow.box only if it started with emitters).
                          "glow.emitters", "glow.core_radius", "glow.intensity", "glow.tone_map",
                          "glow.exposure"})
    if (path == key) return true;
  return false;
}

void requireTable(const std::string& key, double v, const std::string& name) {
  for (const Check& c : sceneKeyChecks(key))
    if (!c.of_length) require(c, name, v, numText(v));
}

Scene parseScene(const SceneText& text, const std::vector<std::string>& overrides) {
  const std::string& path = text.path;
  YAML::Node root(YAML::NodeType::Map);
  Origin origin{std::filesystem::current_path(), {}};
  if (!path.empty()) {
    try {
      root = YAML::Load(text.yaml);
    } catch (const YAML::Exception& e) {
      throw InputError("scene file " + path + ": not valid YAML: " + e.what());
    }
    if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
    if (!root.IsMap()) throw InputError("scene file " + path + ": top level must be a map of keys");
    origin.base_dir = std::filesystem::absolute(path).parent_path();
  }
  checkKeys(root, "");
  for (const std::string& o : overrides) {
    auto eq = o.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set " + o + ": expected key.path=value");
    std::string key = o.substr(0, eq);
    const std::optional<FieldEntryKey> field = parseFieldEntryKey(key);
    if (!field && !findSceneKey(key)) throw InputError("--set " + o + ": unknown scene key '" + key + "'");
    YAML::Node v;
    try {
      v = YAML::Load(o.substr(eq + 1));
    } catch (const YAML::Exception& e) {
      throw InputError("--set " + o + ": value is not valid YAML: " + e.what());
    }
    if (field) {
      setFieldEntryKey(root, *field, key, v);
      continue;
    }
    setPath(root, splitPath(key), 0, v);
    origin.overridden.insert(key);
  }

  Reader r(root);
  Scene s;
  readTypedKeys(r, origin, s);

  // What a row cannot say, section by section (scene/scene_reader.h): the keys with structure of
  // their own, `auto` values derived from other keys, and the rules between a section's keys.
  checkVolumeKeys(s);
  s.time.volume_files = readSeries(r, "volume.files", origin);
  checkParticleKeys(r, s.particles);
  s.time.particle_files = readSeries(r, "particles.files", origin);
  checkTimeKeys(s);
  readGlowKeys(r, s);
  s.surfaces = parseSurfaces(r.get("surfaces"), origin.base_dir);
  checkRenderKeys(s);
  s.render.isovalues = parseIsovalues(r.get("render.isovalues"));
  // The rules between sections.
  if (!s.hasVolume() && !s.particles.enabled() && !s.glow.enabled() && s.surfaces.empty() &&
      !(r.get("volumes").IsSequence() && r.get("volumes").size() > 0))
    throw InputError("the scene has nothing to render: volume.procedural is none with no "
                     "volume.file, neither particles.file nor particles.procedural is set, "
                     "glow.emitters is empty and there are no surfaces");
  if (!s.hasVolume() && !s.particles.enabled() && s.surfaces.empty() && !s.glow.box)
    throw InputError("scene key 'glow.box': a scene of glow emitters alone must set the box the "
                     "glow is integrated in (auto takes the volume's and particles' bounds, and "
                     "there are none)");
  readTransferKeys(r, origin, s.transfer);
  const std::optional<bool> first_preint_auto = readVolumesKey(r, origin, root, s);
  checkCameraKeys(s);
  readClipKeys(r, s);

  // Glow emitters alone need no cut: every brick would evaluate every emitter again over its
  // part of each ray (d = 2 draws about 3x the pixels of d = 1 at 512^2, docs/glow.md).
  const bool glow_alone = s.glow.enabled() && !s.hasVolume() && !s.particles.enabled() && s.surfaces.empty();
  if (r.isAuto("bricks.per_axis")) s.bricks.per_axis = glow_alone ? 1 : 2;
  s.adaptive.tolerance /= 100.0;  // given in percent
  // transfer.preintegrated `auto`: on where the opacity is steep and pre-integration is supported.
  const bool preint_auto = first_preint_auto.value_or(r.isAuto("transfer.preintegrated")) && !s.hasFields();
  if (preint_auto)
    s.transfer.preintegrated = s.adaptive.tolerance == 0.0 && s.render.sample_spacing <= 2.0 &&
                               hasSteepOpacity(s.transfer.points);
  if (s.transfer.preintegrated && s.adaptive.tolerance > 0.0)
    throw InputError("scene keys 'transfer.preintegrated' and 'adaptive.tolerance': pre-integration "
                     "is not supported with adaptive sampling; set transfer.preintegrated: false or "
                     "adaptive.tolerance: 0");
  applyIsosurfaceRules(r, s);
  s.transfer.preintegrated_auto = preint_auto && s.adaptive.tolerance == 0.0 &&
                                  s.render.blend == VolumeBlend::kComposite && s.render.sample_spacing_auto;
  // A segment's ends lie up to half a step beyond the brick that owns it; the bricks' one-voxel
  // ghost layer holds them for steps up to 2 voxels (beyond, brick faces showed seams of 55-74/255).
  if (s.transfer.preintegrated && s.render.sample_spacing > 2.0)
    throw InputError("scene keys 'transfer.preintegrated' and 'render.sample_spacing': "
                     "pre-integration needs render.sample_spacing <= 2 voxels (got " +
                     std::to_string(s.render.sample_spacing) + ")");
  // The adaptive ray caster reads each block's own samples only (clamped to the block), so a
  // difference one voxel across a block face would read the wrong field: refused, not approximated.
  if (s.render.shading.enabled && s.adaptive.tolerance > 0.0)
    throw InputError("scene keys 'render.shading' and 'adaptive.tolerance': gradient shading is not "
                     "available with adaptive sampling; set render.shading: false or "
                     "adaptive.tolerance: 0");
  return s;
}

}  // namespace sortlast
