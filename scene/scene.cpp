#include "scene/scene.h"

#include <glob.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "transfer/colormap_presets.h"
#include "common/error.h"
#include "scene/file_steps.h"

namespace sortlast {

namespace {

constexpr long long kDefaultProceduralParticles = 4096;  // particles.count: auto, procedural

bool isMapPrefix(const std::string& path) {
  for (const SceneKey& k : sceneKeys())
    if (std::string(k.path).rfind(path + ".", 0) == 0) return true;
  return false;
}

std::vector<std::string> splitPath(const std::string& path) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t i = 0; i <= path.size(); ++i)
    if (i == path.size() || path[i] == '.') {
      parts.push_back(path.substr(start, i - start));
      start = i + 1;
    }
  return parts;
}

std::string where(const YAML::Node& n) {
  auto m = n.Mark();
  return m.line >= 0 ? " (line " + std::to_string(m.line + 1) + ")" : "";
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

std::string numText(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// A value as range errors show it: numbers as %g, integers in full.
template <class V>
std::string valueText(V v) {
  if constexpr (std::is_integral_v<V>) return std::to_string(v);
  else return numText(v);
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

// One of the table's checks; `r` gives the value as written, for a message that shows it.
void require(const Check& c, const std::string& key, double v, const std::string& value,
             const Reader* r = nullptr) {
  if (c.says && !c.allowed.admits(v)) {
    YAML::Node n = r ? r->get(key) : YAML::Node();
    throw InputError(c.error(key, value, n.IsScalar() ? n.Scalar() : ""));
  }
}

// A number that parseScene's own code read, by the table's checks of `key` (named `name` in the
// message).
void requireTable(const std::string& key, double v, const std::string& name) {
  for (const Check& c : sceneKeyChecks(key))
    if (!c.of_length) require(c, name, v, numText(v));
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

// Every key the table types, in the table's order: its value (`auto` leaves the field to its
// default or to parseScene), checked, into its field.
void readTypedKeys(const Reader& r, const Origin& o, Scene& s) {
  for (const SceneKey& k : sceneKeys()) {
    if (k.auto_value) {
      const bool is_auto = r.isAuto(k.path);
      if (k.auto_value->flag) k.auto_value->flag(s) = is_auto;
      if (is_auto) continue;
    }
    std::visit([&](const auto& type) { read(type, k.path, r, o, s); }, k.type);
  }
}

// The particles.* rules between keys (each key's own range is the table's).
void checkParticles(const Reader& r, ParticleDesc& p) {
  if (!p.file.empty() && p.procedural != "none")
    throw InputError(
        "scene keys 'particles.file' and 'particles.procedural' are both set: use one "
        "(set particles.procedural to none to read the file)");
  if (r.isAuto("particles.count") && p.file.empty() && p.procedural != "none")
    p.count = kDefaultProceduralParticles;
  if (!p.radius_dataset.empty())
    throw InputError("scene key 'particles.radius_dataset': per-particle radii (" + p.radius_dataset +
                     ") are not supported: every particle has particles.radius; remove the key");
  validateAnisotropic(p.anisotropic);
  if (p.anisotropicOn() && p.method != ParticleMethod::kGrid) {
    const std::string method(nameOf(p.method));
    throw InputError("scene key 'particles.smoothing': anisotropic needs particles.method: grid (the " +
                     method + " method draws round particles only); got particles.method: " + method);
  }
}

// volume.files / particles.files: a list of files, or one glob pattern (sorted matches).
std::vector<std::string> readSeries(const Reader& r, const std::string& key, const Origin& o) {
  YAML::Node n = r.get(key);
  auto resolve = [&](const std::string& f) { return o.resolve(key, f); };
  std::vector<std::string> files;
  if (n.IsNull() || (n.IsScalar() && n.Scalar().empty())) return files;
  if (n.IsSequence()) {
    for (const auto& e : n) {
      if (!e.IsScalar() || e.Scalar().empty())
        throw InputError("scene key '" + key + "': expected a list of file names" + where(e));
      files.push_back(resolve(e.Scalar()));
    }
    if (files.empty()) throw InputError("scene key '" + key + "': the list is empty" + where(n));
    return files;
  }
  if (!n.IsScalar()) throw InputError("scene key '" + key + "': expected a glob pattern or a list of files" + where(n));
  std::string pattern = resolve(n.Scalar());
  glob_t g{};
  int rc = glob(pattern.c_str(), GLOB_ERR, nullptr, &g);
  for (size_t i = 0; rc == 0 && i < g.gl_pathc; ++i) files.push_back(g.gl_pathv[i]);
  globfree(&g);
  if (files.empty()) throw InputError("scene key '" + key + "': no file matches '" + pattern + "'");
  std::sort(files.begin(), files.end());
  return files;
}

// glow.emitters (scene/glow_scene.h has the emitters' own keys) and glow.box. The emitters'
// rates run per frame of an orbit and on through the steps of a series.
void readGlow(const Reader& r, Scene& s) {
  GlowSpec& g = s.glow;
  const int per_step = std::max(1, s.orbit.frames);
  g.emitters = parseGlowEmitters(r.get("glow.emitters"), s.time.steps * per_step);
  g.first_frame = s.time.step * per_step;
  if (!r.isAuto("glow.box")) {
    YAML::Node n = r.get("glow.box");
    if (!n.IsSequence() || n.size() != 2)
      throw InputError("scene key 'glow.box': expected auto or [[x0, y0, z0], [x1, y1, z1]]" + where(n));
    Box3 b;
    for (int c = 0; c < 2; ++c) {
      std::vector<double> v;
      try {
        for (const auto& x : n[c]) v.push_back(x.as<double>());
      } catch (const YAML::Exception&) {
        v.clear();
      }
      if (v.size() != 3)
        throw InputError("scene key 'glow.box': each corner is a list of 3 numbers" + where(n));
      for (double x : v)
        if (!std::isfinite(x)) throw InputError("scene key 'glow.box': values must be finite" + where(n));
      for (double x : v) requireTable("glow.box", x, "glow.box");
      (c == 0 ? b.lo : b.hi) = glm::dvec3{v[0], v[1], v[2]};
    }
    for (int a = 0; a < 3; ++a)
      if (!(b.hi[a] - b.lo[a] >= kMinLength))
        throw InputError("scene key 'glow.box': needs lo < hi on every axis (by at least 1e-12)" + where(n));
    g.box = b;
  }
}

// transfer.points (or transfer.preset), transfer.range and transfer.colormap.
void readTransfer(const Reader& r, const Origin& o, TransferSpec& tf) {
  YAML::Node pts = r.get("transfer.points");
  if (pts.IsNull()) {
    tf.points = TransferFunction::preset(r.as<std::string>("transfer.preset"));
  } else {
    if (!pts.IsSequence() || pts.size() == 0)
      throw InputError("scene key 'transfer.points': expected a list of [value, r, g, b, a]" + where(pts));
    for (const auto& p : pts) {
      std::vector<double> v;
      try {
        for (const auto& e : p) v.push_back(e.as<double>());
      } catch (const YAML::Exception&) {
        v.clear();
      }
      if (v.size() != 5)
        throw InputError("scene key 'transfer.points': each point is [value, r, g, b, a]" + where(p));
      tf.points.push_back({v[0], v[1], v[2], v[3], v[4]});
    }
  }
  if (!r.isAuto("transfer.range")) {
    auto v = r.numbers("transfer.range", 2);
    if (!(v[1] > v[0])) throw InputError("scene key 'transfer.range': needs lo < hi");
    // Samples are floats on the GPU: the range must be one, and wide enough not to collapse there.
    for (double x : v) requireTable("transfer.range", x, "transfer.range");
    if (v[1] - v[0] < 1e-6 * std::max(std::abs(v[0]), std::abs(v[1])))
      throw InputError("scene key 'transfer.range': [" + numText(v[0]) + ", " + numText(v[1]) +
                       "] is narrower than float precision at that magnitude (hi - lo must be at "
                       "least 1e-6 of |hi|)");
    tf.range = std::make_pair(v[0], v[1]);
  }
  // Validate the points now (range and unit length are placeholders until the data is known).
  TransferFunction(tf.points, 0.0, 1.0, tf.unit_length.value_or(1.0));
  // A colour map replaces the points' colours (their opacity stays): resolved here, once per
  // parse, so the rest of the program sees plain control points.
  if (!r.get("transfer.colormap").IsNull()) tf.colormap = r.as<std::string>("transfer.colormap");
  if (!tf.colormap.empty()) {
    try {
      const bool given = o.fromOverride("transfer.colormap");
      ColourMap map =
          loadColourMap(tf.colormap, given ? std::filesystem::current_path() : o.base_dir);
      tf.points = applyColourMap(tf.points, map.sampled());
    } catch (const InputError& e) {
      throw InputError(std::string("scene key 'transfer.colormap': ") + e.what());
    }
  }
}

}  // namespace

TransferFunction TransferSpec::build(double data_min, double data_max, double min_spacing) const {
  double lo = range ? range->first : data_min, hi = range ? range->second : data_max;
  if (!range && !(hi > lo)) hi = lo + 1.0;  // constant volume: any non-empty range will do
  return TransferFunction(points, lo, hi, unit_length.value_or(min_spacing));
}

std::vector<Camera> Scene::frameCameras(const Box3& bounds) const {
  Camera base = camera;
  // No volume and no particles leaves an empty box; one particle, a point: any camera that looks
  // at where the (absent) data would be will do.
  const bool empty = isEmpty(bounds);
  glm::dvec3 e = bounds.extent();
  double largest = glm::max(e.x, glm::max(e.y, e.z));
  double extent = empty || !(largest > 0.0) ? 1.0 : largest;
  if (look_at_auto) base.look_at = empty ? glm::dvec3(0.0) : bounds.centre();
  if (camera_auto) {
    // Far enough that the box's bounding sphere (about the look-at point) fits in the vertical
    // and the horizontal field of view, with 2% to spare: the whole scene is in the frame
    // whatever its shape and the image's aspect. (The viewer's reset, viewer/orbit.js
    // frameBounds, frames the same way.)
    glm::dvec3 centre = empty ? glm::dvec3(0.0) : bounds.centre();
    double radius = empty || !(largest > 0.0) ? 0.5 * std::sqrt(3.0) : 0.5 * glm::length(e);
    radius += glm::length(centre - base.look_at);
    double vhalf = 0.5 * base.fov_deg * 3.14159265358979323846 / 180.0;
    double hhalf = std::atan(std::tan(vhalf) * double(base.width) / base.height);
    double dist = 1.02 * radius / std::sin(std::min(vhalf, hhalf));
    base.position = base.look_at + dist * glm::normalize(glm::dvec3(0.55, 0.35, 1.0));
  }
  if (orbit.frames == 0) return {base};
  std::vector<Camera> cams;
  double radius = orbit.radius.value_or(2.0 * extent);
  for (int i = 0; i < orbit.frames; ++i)
    cams.push_back(orbitCamera(base, base.look_at, radius, orbit.elevation, i, orbit.frames, orbit.start));
  return cams;
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
  for (const char* prefix : {"camera.", "image.", "transfer.", "compositing.", "time.step"})
    if (path.rfind(prefix, 0) == 0) return true;
  for (const char* key : {"render.sample_spacing", "render.method", "render.ert_threshold",
                          "render.shading", "render.shading_ambient", "render.shading_diffuse",
                          "render.shading_specular", "render.shading_shininess",
                          "render.adaptive_step", "render.adaptive_tolerance",
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

bool hasSteepOpacity(const std::vector<TfPoint>& points) {
  for (size_t i = 1; i < points.size(); ++i) {
    const double dx = points[i].value - points[i - 1].value, da = std::abs(points[i].a - points[i - 1].a);
    if (da > 0.0 && da >= kSteepOpacitySlope * dx) return true;
  }
  return false;
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
    if (!findSceneKey(key)) throw InputError("--set " + o + ": unknown scene key '" + key + "'");
    YAML::Node v;
    try {
      v = YAML::Load(o.substr(eq + 1));
    } catch (const YAML::Exception& e) {
      throw InputError("--set " + o + ": value is not valid YAML: " + e.what());
    }
    setPath(root, splitPath(key), 0, v);
    origin.overridden.insert(key);
  }

  Reader r(root);
  Scene s;
  readTypedKeys(r, origin, s);

  // What a row cannot say: the keys with structure of their own, `auto` values derived from other
  // keys, and the rules between keys.
  VolumeDesc& vol = s.volume;
  for (int a = 0; a < 3; ++a)
    requireTable("volume.spacing", vol.grid.spacing[a] * (vol.grid.dims[a] - 1),
                 "volume.spacing (times volume.dims - 1: the volume's extent)");
  s.time.volume_files = readSeries(r, "volume.files", origin);
  if (!s.time.volume_files.empty() && !vol.file.empty())
    throw InputError("scene keys 'volume.file' and 'volume.files' are both set: use one");
  checkParticles(r, s.particles);
  s.time.particle_files = readSeries(r, "particles.files", origin);
  if (!s.time.particle_files.empty() && (!s.particles.file.empty() || s.particles.procedural != "none"))
    throw InputError("scene key 'particles.files' is set with 'particles.file' or "
                     "'particles.procedural': use one");
  if (!s.time.volume_files.empty() && !s.time.particle_files.empty() &&
      s.time.volume_files.size() != s.time.particle_files.size())
    throw InputError("scene keys 'volume.files' and 'particles.files' name " +
                     std::to_string(s.time.volume_files.size()) + " and " +
                     std::to_string(s.time.particle_files.size()) + " steps: a series needs one of each per step");
  // Steps inside one file (the records of a 4-D NetCDF variable, an HDF5 volume.dataset with
  // {step}) are the file's to say: parsing reads no data file, so those are counted, and time.step
  // checked against them, by resolveFileSteps (scene/file_steps.h) when the scene is loaded. What
  // needs no file is checked here.
  const bool hdf5_series = vol.dataset.find("{step}") != std::string::npos;
  if (hdf5_series && !s.time.volume_files.empty())
    throw InputError("volume.dataset " + vol.dataset + ": {step} makes one file a time series; with "
                     "volume.files (one file per step) name the dataset without {step}");
  if (hdf5_series && !vol.file.empty() && vol.formatOf() != VolumeFormat::kHdf5)
    throw InputError("volume.dataset " + vol.dataset + ": {step} needs an HDF5 volume.file, not " + vol.file);
  s.time.steps = int(std::max({size_t(1), s.time.volume_files.size(), s.time.particle_files.size()}));
  // (With a particle series beside a file's steps, the two must agree: its length bounds the step.)
  const bool steps_known = !hasFileSteps(s) || !s.time.particle_files.empty();
  if (s.time.step < 0 || (steps_known && s.time.step >= s.time.steps))
    throw InputError("scene key 'time.step': " + std::to_string(s.time.step) + " is out of range: the scene has " +
                     std::to_string(s.time.steps) + " time step(s), 0 ... " + std::to_string(s.time.steps - 1));
  if (!s.time.volume_files.empty()) vol.file = s.time.volume_files[size_t(s.time.step)];
  if (!s.time.particle_files.empty()) s.particles.file = s.time.particle_files[size_t(s.time.step)];
  readGlow(r, s);
  s.surfaces = parseSurfaces(r.get("surfaces"), origin.base_dir);
  if (s.render.device >= 0 && s.render.backend != GlBackend::kEgl)
    throw InputError("scene key 'render.device': device " + std::to_string(s.render.device) +
                     " names an EGL device, but render.backend is " + std::string(nameOf(s.render.backend)) +
                     " (set render.backend: egl, or render.device: auto)");
  if (!s.hasVolume() && !s.particles.enabled() && !s.glow.enabled() && s.surfaces.empty())
    throw InputError("the scene has nothing to render: volume.procedural is none with no "
                     "volume.file, neither particles.file nor particles.procedural is set, "
                     "glow.emitters is empty and there are no surfaces");
  if (!s.hasVolume() && !s.particles.enabled() && s.surfaces.empty() && !s.glow.box)
    throw InputError("scene key 'glow.box': a scene of glow emitters alone must set the box the "
                     "glow is integrated in (auto takes the volume's and particles' bounds, and "
                     "there are none)");
  readTransfer(r, origin, s.transfer);

  Camera& cam = s.camera;
  const Allowed& size = sceneKeyChecks("image.width").front().allowed;
  if (!size.admits(cam.width) || !size.admits(cam.height))
    throw InputError("image size " + std::to_string(cam.width) + " x " + std::to_string(cam.height) +
                     ": image.width and image.height must be " + size.phrase());
  if (!s.camera_auto && s.orbit.frames == 0) {
    if (glm::length(cam.look_at - cam.position) == 0.0)
      throw InputError("camera.position equals camera.look_at: no view direction");
    if (glm::length(glm::cross(cam.forward(), cam.up)) < 1e-9)
      throw InputError("camera.up is parallel to the view direction");
  }

  // Glow emitters alone need no cut: every brick would evaluate every emitter again over its
  // part of each ray (d = 2 draws about 3x the pixels of d = 1 at 512^2, docs/glow.md).
  const bool glow_alone = s.glow.enabled() && !s.hasVolume() && !s.particles.enabled() && s.surfaces.empty();
  if (r.isAuto("bricks.per_axis")) s.bricks.per_axis = glow_alone ? 1 : 2;
  s.adaptive.tolerance /= 100.0;  // given in percent
  // transfer.preintegrated `auto`: on where the opacity is steep and pre-integration is supported.
  if (r.isAuto("transfer.preintegrated"))
    s.transfer.preintegrated = s.adaptive.tolerance == 0.0 && s.render.sample_spacing <= 2.0 &&
                               hasSteepOpacity(s.transfer.points);
  if (s.transfer.preintegrated && s.adaptive.tolerance > 0.0)
    throw InputError("scene keys 'transfer.preintegrated' and 'adaptive.tolerance': pre-integration "
                     "is not supported with adaptive sampling; set transfer.preintegrated: false or "
                     "adaptive.tolerance: 0");
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
