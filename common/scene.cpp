#include "common/scene.h"

#include <glob.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "common/colormap_presets.h"
#include "common/error.h"

namespace sortlast {

namespace {

constexpr long long kDefaultProceduralParticles = 4096;  // particles.count: auto, procedural
constexpr long long kMaxParticles = 1LL << 31;            // 24 GiB of centres: surely a typo

const SceneKey* findKey(const std::string& path) {
  for (const SceneKey& k : sceneKeys())
    if (path == k.path) return &k;
  return nullptr;
}

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
    if (findKey(full)) continue;
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
      if (!n.IsMap() || !n[p]) return YAML::Load(findKey(path)->default_yaml);
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

// Range checks against what float math on the GPU can hold (common/box.h): each names the key
// and the value, before the value can turn into an overflow or a misleading later error.
void checkCoordinates(const std::string& key, const glm::dvec3& v) {
  for (int a = 0; a < 3; ++a)
    if (std::abs(v[a]) > kMaxCoordinate)
      throw InputError(
          "scene key '" + key + "': " + numText(v[a]) +
          " is beyond +-1e18, which float math on the GPU cannot hold (it squares distances)");
}

void checkLength(const std::string& key, double v) {
  if (!(v >= kMinLength && v <= kMaxCoordinate))
    throw InputError("scene key '" + key + "': " + numText(v) +
                     " is outside [1e-12, 1e18], the lengths float math on the GPU can hold");
}

// The particles.* keys. Relative file paths are relative to the scene file (not for --set, whose
// paths are the user's, relative to where they run).
ParticleDesc readParticles(const Reader& r, const std::filesystem::path& base_dir,
                           bool file_from_override) {
  ParticleDesc p;
  p.file = r.as<std::string>("particles.file");
  if (!p.file.empty() && std::filesystem::path(p.file).is_relative() && !file_from_override)
    p.file = (base_dir / p.file).string();
  p.procedural = r.as<std::string>("particles.procedural");
  if (p.procedural != "none" && p.procedural != "layers" && p.procedural != "splash")
    throw InputError("scene key 'particles.procedural': expected none, layers or splash, got '" +
                     p.procedural + "'");
  if (!p.file.empty() && p.procedural != "none")
    throw InputError(
        "scene keys 'particles.file' and 'particles.procedural' are both set: use one "
        "(set particles.procedural to none to read the file)");
  p.format = r.as<std::string>("particles.format");
  if (p.format != "auto" && p.format != "vtk" && p.format != "raw" && p.format != "csv")
    throw InputError("scene key 'particles.format': expected auto, vtk, raw or csv, got '" +
                     p.format + "'");
  if (!r.isAuto("particles.count")) {
    p.count = r.as<long long>("particles.count");
    if (p.count < 0 || p.count > kMaxParticles)
      throw InputError("scene key 'particles.count': must be auto or in [0, " +
                       std::to_string(kMaxParticles) + "], got " + std::to_string(p.count));
  } else if (p.file.empty() && p.procedural != "none") {
    p.count = kDefaultProceduralParticles;
  }
  auto positive = [&](const char* key) {
    double v = r.as<double>(key);
    if (!(v > 0.0) || !std::isfinite(v))
      throw InputError(std::string("scene key '") + key + "': must be a finite number > 0");
    return v;
  };
  p.spacing = positive("particles.spacing");
  p.radius = positive("particles.radius");
  if (!r.isAuto("particles.influence")) p.influence = positive("particles.influence");
  checkLength("particles.spacing", p.spacing);
  checkLength("particles.radius", p.radius);
  if (p.influence) checkLength("particles.influence", *p.influence);
  p.threshold = r.as<double>("particles.threshold");
  if (!(p.threshold > 0.0 && p.threshold < 1.0))
    throw InputError("scene key 'particles.threshold': must be in (0, 1)");
  p.colour = r.vec3("particles.color");
  for (int c = 0; c < 3; ++c)
    if (p.colour[c] < 0.0 || p.colour[c] > 1.0)
      throw InputError("scene key 'particles.color': entries must be in [0, 1]");
  p.method = r.as<std::string>("particles.method");
  if (p.method != "billboards" && p.method != "grid" && p.method != "slices")
    throw InputError("scene key 'particles.method': expected billboards, grid or slices, got '" + p.method + "'");
  // Below 1/20 h the lattice needs 8000 points per h^3 (memory and splat time grow as the inverse
  // cube); above h the lattice cannot even hold a lone particle's surface (radius 0.23 h).
  p.slice_spacing = r.as<double>("particles.slice_spacing");
  if (!(p.slice_spacing >= kMinSliceSpacing && p.slice_spacing <= kMaxSliceSpacing)) {
    std::ostringstream msg;
    msg << "scene key 'particles.slice_spacing': must be in [" << kMinSliceSpacing << ", " << kMaxSliceSpacing
        << "] (units of h), got " << r.as<std::string>("particles.slice_spacing");
    throw InputError(msg.str());
  }
  p.step = positive("particles.step");
  p.max_samples = r.as<int>("particles.max_samples");
  if (p.max_samples < 1) throw InputError("scene key 'particles.max_samples': must be >= 1");
  p.refine_iterations = r.as<int>("particles.refine_iterations");
  if (p.refine_iterations < 0)
    throw InputError("scene key 'particles.refine_iterations': must be >= 0");
  p.cull = r.as<bool>("particles.cull");
  p.samples_per_pass = r.as<int>("particles.samples_per_pass");
  if (p.samples_per_pass != 4 && p.samples_per_pass != 8)
    throw InputError("scene key 'particles.samples_per_pass': must be 4 or 8");
  p.smoothing = r.as<std::string>("particles.smoothing");
  if (p.smoothing != "none" && p.smoothing != "anisotropic")
    throw InputError("scene key 'particles.smoothing': expected none or anisotropic, got '" +
                     p.smoothing + "'");
  AnisotropicParams& a = p.anisotropic;
  a.splash_scale = r.as<double>("particles.anisotropic.splash_scale");
  a.surface_scale = r.as<double>("particles.anisotropic.surface_scale");
  a.rho_splash = r.as<double>("particles.anisotropic.rho_splash");
  a.rho_surface = r.as<double>("particles.anisotropic.rho_surface");
  a.neighbourhood = r.as<double>("particles.anisotropic.neighbourhood");
  a.max_axis_ratio = r.as<double>("particles.anisotropic.max_axis_ratio");
  validateAnisotropic(a);
  if (p.anisotropicOn() && p.method != "grid")
    throw InputError("scene key 'particles.smoothing': anisotropic needs particles.method: grid (the " +
                     p.method + " method draws round particles only); got particles.method: " + p.method);
  return p;
}

// volume.files / particles.files: a list of files, or one glob pattern (sorted matches). Relative
// names are relative to the scene file (to the working directory when given with --set).
std::vector<std::string> readSeries(const Reader& r, const std::string& key,
                                    const std::filesystem::path& base_dir, bool from_override) {
  YAML::Node n = r.get(key);
  auto resolve = [&](const std::string& f) {
    return std::filesystem::path(f).is_relative() && !from_override ? (base_dir / f).string() : f;
  };
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

// The glow.* keys (common/glow_scene.h has the emitters' own).
// The emitters' rates run per frame of an orbit and on through the steps of a series.
GlowSpec readGlow(const Reader& r, int time_step, int time_steps) {
  GlowSpec g;
  const int per_step = std::max(1, r.as<int>("camera.orbit.frames"));  // checked >= 0 with the camera
  g.emitters = parseGlowEmitters(r.get("glow.emitters"), time_steps * per_step);
  g.first_frame = time_step * per_step;
  g.core_radius = r.as<double>("glow.core_radius");
  checkLength("glow.core_radius", g.core_radius);
  g.intensity = r.as<double>("glow.intensity");
  if (!(g.intensity >= 0.0 && g.intensity <= 1e30))
    throw InputError("scene key 'glow.intensity': must be in [0, 1e30]");
  g.tone_map = r.as<std::string>("glow.tone_map");
  if (g.tone_map != "none" && g.tone_map != "exponential")
    throw InputError("scene key 'glow.tone_map': expected none or exponential, got '" + g.tone_map + "'");
  g.exposure = r.as<double>("glow.exposure");
  if (!(g.exposure > 0.0 && g.exposure <= 1e30))
    throw InputError("scene key 'glow.exposure': must be in (0, 1e30]");
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
      glm::dvec3 p{v[0], v[1], v[2]};
      for (double x : v)
        if (!std::isfinite(x)) throw InputError("scene key 'glow.box': values must be finite" + where(n));
      checkCoordinates("glow.box", p);
      (c == 0 ? b.lo : b.hi) = p;
    }
    for (int a = 0; a < 3; ++a)
      if (!(b.hi[a] - b.lo[a] >= kMinLength))
        throw InputError("scene key 'glow.box': needs lo < hi on every axis (by at least 1e-12)" + where(n));
    g.box = b;
  }
  return g;
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
  if (orbit_frames == 0) return {base};
  std::vector<Camera> cams;
  double radius = orbit_radius.value_or(2.0 * extent);
  for (int i = 0; i < orbit_frames; ++i)
    cams.push_back(orbitCamera(base, base.look_at, radius, orbit_elevation, i, orbit_frames));
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
  std::filesystem::path base_dir = std::filesystem::current_path();
  if (!path.empty()) {
    try {
      root = YAML::Load(text.yaml);
    } catch (const YAML::Exception& e) {
      throw InputError("scene file " + path + ": not valid YAML: " + e.what());
    }
    if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
    if (!root.IsMap()) throw InputError("scene file " + path + ": top level must be a map of keys");
    base_dir = std::filesystem::absolute(path).parent_path();
  }
  checkKeys(root, "");
  bool file_from_override = false, particles_file_from_override = false;
  bool files_from_override = false, particles_files_from_override = false;
  bool colormap_from_override = false;
  for (const std::string& o : overrides) {
    auto eq = o.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set " + o + ": expected key.path=value");
    std::string key = o.substr(0, eq);
    if (!findKey(key)) throw InputError("--set " + o + ": unknown scene key '" + key + "'");
    YAML::Node v;
    try {
      v = YAML::Load(o.substr(eq + 1));
    } catch (const YAML::Exception& e) {
      throw InputError("--set " + o + ": value is not valid YAML: " + e.what());
    }
    setPath(root, splitPath(key), 0, v);
    if (key == "volume.file") file_from_override = true;
    if (key == "particles.file") particles_file_from_override = true;
    if (key == "volume.files") files_from_override = true;
    if (key == "particles.files") particles_files_from_override = true;
    if (key == "transfer.colormap") colormap_from_override = true;
  }

  Reader r(root);
  Scene s;
  VolumeDesc& vol = s.volume;
  vol.file = r.as<std::string>("volume.file");
  if (!vol.file.empty() && std::filesystem::path(vol.file).is_relative() && !file_from_override)
    vol.file = (base_dir / vol.file).string();
  vol.procedural = r.as<std::string>("volume.procedural");
  auto dims = r.numbers("volume.dims", 3);
  for (int a = 0; a < 3; ++a) {
    if (dims[a] != std::floor(dims[a]) || dims[a] < 2 || dims[a] > 1 << 20)
      throw InputError("scene key 'volume.dims': entries must be integers in [2, 2^20]");
    vol.grid.dims[a] = int(dims[a]);
  }
  vol.grid.spacing = r.vec3("volume.spacing");
  for (int a = 0; a < 3; ++a) {
    checkLength("volume.spacing", vol.grid.spacing[a]);
    checkLength("volume.spacing (times volume.dims - 1: the volume's extent)",
                vol.grid.spacing[a] * (vol.grid.dims[a] - 1));
  }
  vol.type = parseSampleType(r.as<std::string>("volume.type"));
  std::string order = r.as<std::string>("volume.byte_order");
  if (order != "little" && order != "big")
    throw InputError("scene key 'volume.byte_order': expected little or big, got '" + order + "'");
  vol.big_endian = order == "big";
  vol.header_bytes = r.as<long long>("volume.header_bytes");
  if (vol.header_bytes < 0) throw InputError("scene key 'volume.header_bytes': must be >= 0");

  s.time_step = r.as<int>("time.step");
  s.time_cache_mib = r.as<double>("time.cache_mib");
  if (!(s.time_cache_mib >= 0.0 && s.time_cache_mib <= 1e9))
    throw InputError("scene key 'time.cache_mib': must be in [0, 1e9] MiB");
  if (!r.isAuto("limits.memory_mib")) {
    s.memory_limit_mib = r.as<double>("limits.memory_mib");
    if (!(*s.memory_limit_mib > 0.0 && *s.memory_limit_mib <= 1e12))
      throw InputError("scene key 'limits.memory_mib': must be auto or in (0, 1e12] MiB");
  }
  s.volume_files = readSeries(r, "volume.files", base_dir, files_from_override);
  if (!s.volume_files.empty() && !vol.file.empty())
    throw InputError("scene keys 'volume.file' and 'volume.files' are both set: use one");
  s.particles = readParticles(r, base_dir, particles_file_from_override);
  s.particle_files = readSeries(r, "particles.files", base_dir, particles_files_from_override);
  if (!s.particle_files.empty() && (!s.particles.file.empty() || s.particles.procedural != "none"))
    throw InputError("scene key 'particles.files' is set with 'particles.file' or "
                     "'particles.procedural': use one");
  if (!s.volume_files.empty() && !s.particle_files.empty() &&
      s.volume_files.size() != s.particle_files.size())
    throw InputError("scene keys 'volume.files' and 'particles.files' name " +
                     std::to_string(s.volume_files.size()) + " and " +
                     std::to_string(s.particle_files.size()) + " steps: a series needs one of each per step");
  s.time_steps = int(std::max({size_t(1), s.volume_files.size(), s.particle_files.size()}));
  if (s.time_step < 0 || s.time_step >= s.time_steps)
    throw InputError("scene key 'time.step': " + std::to_string(s.time_step) + " is out of range: the scene has " +
                     std::to_string(s.time_steps) + " time step(s), 0 ... " + std::to_string(s.time_steps - 1));
  if (!s.volume_files.empty()) vol.file = s.volume_files[size_t(s.time_step)];
  if (!s.particle_files.empty()) s.particles.file = s.particle_files[size_t(s.time_step)];
  s.glow = readGlow(r, s.time_step, s.time_steps);
  s.surfaces = parseSurfaces(r.get("surfaces"), base_dir);
  if (!s.hasVolume() && !s.particles.enabled() && !s.glow.enabled() && s.surfaces.empty())
    throw InputError("the scene has nothing to render: volume.procedural is none with no "
                     "volume.file, neither particles.file nor particles.procedural is set, "
                     "glow.emitters is empty and there are no surfaces");
  if (!s.hasVolume() && !s.particles.enabled() && s.surfaces.empty() && !s.glow.box)
    throw InputError("scene key 'glow.box': a scene of glow emitters alone must set the box the "
                     "glow is integrated in (auto takes the volume's and particles' bounds, and "
                     "there are none)");

  TransferSpec& tf = s.transfer;
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
    for (double x : v)
      if (std::abs(x) > 1e38)
        throw InputError("scene key 'transfer.range': " + numText(x) +
                         " is beyond float's range (+-3.4e38)");
    if (v[1] - v[0] < 1e-6 * std::max(std::abs(v[0]), std::abs(v[1])))
      throw InputError("scene key 'transfer.range': [" + numText(v[0]) + ", " + numText(v[1]) +
                       "] is narrower than float precision at that magnitude (hi - lo must be at "
                       "least 1e-6 of |hi|)");
    tf.range = std::make_pair(v[0], v[1]);
  }
  if (!r.isAuto("transfer.unit_length")) {
    tf.unit_length = r.as<double>("transfer.unit_length");
    checkLength("transfer.unit_length", *tf.unit_length);
  }
  tf.table_size = r.as<int>("transfer.table_size");
  if (tf.table_size < 2 || tf.table_size > 65536)
    throw InputError("scene key 'transfer.table_size': must be in [2, 65536]");
  // `auto` (the default): on wherever it is supported, decided below once the spacing and adaptive
  // sampling are known.
  const bool preintegrated_auto = r.isAuto("transfer.preintegrated");
  tf.preintegrated = preintegrated_auto ? false : r.as<bool>("transfer.preintegrated");
  // Validate the points now (range and unit length are placeholders until the data is known).
  TransferFunction(tf.points, 0.0, 1.0, tf.unit_length.value_or(1.0));
  // A colour map replaces the points' colours (their opacity stays): resolved here, once per
  // parse, so the rest of the program sees plain control points.
  if (!r.get("transfer.colormap").IsNull()) tf.colormap = r.as<std::string>("transfer.colormap");
  if (!tf.colormap.empty()) {
    try {
      ColourMap map = loadColourMap(tf.colormap, colormap_from_override ? std::filesystem::current_path() : base_dir);
      tf.points = applyColourMap(tf.points, map.sampled());
    } catch (const InputError& e) {
      throw InputError(std::string("scene key 'transfer.colormap': ") + e.what());
    }
  }

  Camera& cam = s.camera;
  cam.width = r.as<int>("image.width");
  cam.height = r.as<int>("image.height");
  if (cam.width <= 0 || cam.height <= 0 || cam.width > 32768 || cam.height > 32768)
    throw InputError("image size " + std::to_string(cam.width) + " x " + std::to_string(cam.height) +
                     ": image.width and image.height must be in [1, 32768]");
  s.background = r.vec3("image.background");
  s.look_at_auto = r.isAuto("camera.look_at");
  cam.look_at = s.look_at_auto ? glm::dvec3(0.0) : r.vec3("camera.look_at");
  checkCoordinates("camera.look_at", cam.look_at);
  s.camera_auto = r.isAuto("camera.position");
  if (!s.camera_auto) cam.position = r.vec3("camera.position");
  checkCoordinates("camera.position", cam.position);
  cam.up = r.vec3("camera.up");
  checkCoordinates("camera.up", cam.up);
  cam.fov_deg = r.as<double>("camera.fov");
  if (!(cam.fov_deg > 0.0 && cam.fov_deg < 180.0))
    throw InputError("scene key 'camera.fov': must be in (0, 180) degrees");
  if (!(glm::length(cam.up) >= kMinLength))
    throw InputError("scene key 'camera.up': must not be zero (its length must be at least 1e-12)");
  s.orbit_frames = r.as<int>("camera.orbit.frames");
  if (s.orbit_frames < 0) throw InputError("scene key 'camera.orbit.frames': must be >= 0");
  s.orbit_elevation = r.as<double>("camera.orbit.elevation");
  if (!(s.orbit_elevation >= -90.0 && s.orbit_elevation <= 90.0))  // NaN too
    throw InputError("scene key 'camera.orbit.elevation': must be in [-90, 90] degrees");
  if (!r.isAuto("camera.orbit.radius")) {
    s.orbit_radius = r.as<double>("camera.orbit.radius");
    if (!(*s.orbit_radius > 0.0)) throw InputError("scene key 'camera.orbit.radius': must be > 0");
    checkLength("camera.orbit.radius", *s.orbit_radius);
  }
  if (!s.camera_auto && s.orbit_frames == 0) {
    if (glm::length(cam.look_at - cam.position) == 0.0)
      throw InputError("camera.position equals camera.look_at: no view direction");
    if (glm::length(glm::cross(cam.forward(), cam.up)) < 1e-9)
      throw InputError("camera.up is parallel to the view direction");
  }

  // Glow emitters alone need no cut: every brick would evaluate every emitter again over its
  // part of each ray (d = 2 draws about 3x the pixels of d = 1 at 512^2, docs/glow.md).
  const bool glow_alone = s.glow.enabled() && !s.hasVolume() && !s.particles.enabled() && s.surfaces.empty();
  s.bricks_per_axis = r.isAuto("bricks.per_axis") ? (glow_alone ? 1 : 2) : r.as<int>("bricks.per_axis");
  if (s.bricks_per_axis < 1 || s.bricks_per_axis > 64)
    throw InputError("scene key 'bricks.per_axis': must be in [1, 64]");
  s.backend = r.as<std::string>("render.backend");
  if (s.backend != "osmesa" && s.backend != "egl")
    throw InputError("scene key 'render.backend': expected osmesa or egl, got '" + s.backend + "'");
  s.sample_spacing = r.as<double>("render.sample_spacing");
  if (!(s.sample_spacing >= 0.01 && s.sample_spacing <= 100.0))
    throw InputError("scene key 'render.sample_spacing': must be in [0.01, 100] voxels");
  s.block_cells = r.as<int>("render.block_cells");
  if (s.block_cells < 1) throw InputError("scene key 'render.block_cells': must be >= 1");
  s.ray_block_cells = r.as<int>("render.ray_block_cells");
  if (s.ray_block_cells < 1) throw InputError("scene key 'render.ray_block_cells': must be >= 1");
  s.volume_method = r.as<std::string>("render.method");
  if (s.volume_method != "slicing" && s.volume_method != "raycast")
    throw InputError("scene key 'render.method': expected slicing or raycast, got '" + s.volume_method + "'");
  s.ert_threshold = r.as<double>("render.ert_threshold");
  if (!(s.ert_threshold > 0.0 && s.ert_threshold <= 1.0))
    throw InputError("scene key 'render.ert_threshold': must be in (0, 1] (1: no early termination)");
  s.shading.enabled = r.as<bool>("render.shading");
  for (auto [key, value] : {std::pair{"render.shading_ambient", &s.shading.ambient},
                            std::pair{"render.shading_diffuse", &s.shading.diffuse},
                            std::pair{"render.shading_specular", &s.shading.specular}}) {
    *value = r.as<double>(key);
    if (!(*value >= 0.0 && *value <= 100.0))
      throw InputError(std::string("scene key '") + key + "': must be in [0, 100]");
  }
  s.shading.shininess = r.as<double>("render.shading_shininess");
  if (!(s.shading.shininess >= 1.0 && s.shading.shininess <= 1000.0))
    throw InputError("scene key 'render.shading_shininess': must be in [1, 1000]");
  s.adaptive_step = r.as<bool>("render.adaptive_step");
  s.adaptive_step_tolerance = r.as<double>("render.adaptive_tolerance");
  if (!(s.adaptive_step_tolerance > 0.0 && s.adaptive_step_tolerance <= 1.0))
    throw InputError("scene key 'render.adaptive_tolerance': must be in (0, 1]");
  s.strategy = r.as<std::string>("compositing.strategy");
  if (s.strategy != "direct" && s.strategy != "binary-swap" && s.strategy != "radix-k")
    throw InputError("scene key 'compositing.strategy': expected direct, binary-swap or radix-k, got '" +
                     s.strategy + "'");
  s.radix = r.as<int>("compositing.radix");
  if (s.radix < 2) throw InputError("scene key 'compositing.radix': must be >= 2");
  s.precision = r.as<std::string>("compositing.precision");
  if (s.precision != "float" && s.precision != "rgba8")
    throw InputError("scene key 'compositing.precision': expected float or rgba8, got '" +
                     s.precision + "'");
  s.overlap = r.as<bool>("compositing.overlap");
  s.rle = r.as<bool>("compositing.rle");
  s.adaptive_tolerance = r.as<double>("adaptive.tolerance");
  if (!(s.adaptive_tolerance >= 0.0 && s.adaptive_tolerance <= 100.0))
    throw InputError("scene key 'adaptive.tolerance': must be in [0, 100] percent");
  s.adaptive_tolerance /= 100.0;
  if (preintegrated_auto)
    s.transfer.preintegrated = s.adaptive_tolerance == 0.0 && s.sample_spacing <= 2.0 &&
                               hasSteepOpacity(s.transfer.points);
  if (s.transfer.preintegrated && s.adaptive_tolerance > 0.0)
    throw InputError("scene keys 'transfer.preintegrated' and 'adaptive.tolerance': pre-integration "
                     "is not supported with adaptive sampling; set transfer.preintegrated: false or "
                     "adaptive.tolerance: 0");
  // A segment's ends lie up to half a step beyond the brick that owns it; the bricks' one-voxel
  // ghost layer holds them for steps up to 2 voxels (beyond, brick faces showed seams of 55-74/255).
  if (s.transfer.preintegrated && s.sample_spacing > 2.0)
    throw InputError("scene keys 'transfer.preintegrated' and 'render.sample_spacing': "
                     "pre-integration needs render.sample_spacing <= 2 voxels (got " +
                     std::to_string(s.sample_spacing) + ")");
  s.adaptive_blocks = r.as<int>("adaptive.blocks");
  if (s.adaptive_blocks < 1 || s.adaptive_blocks > 256 || (s.adaptive_blocks & (s.adaptive_blocks - 1)))
    throw InputError("scene key 'adaptive.blocks': must be a power of two in [1, 256], got " +
                     std::to_string(s.adaptive_blocks));
  // The adaptive ray caster reads each block's own samples only (clamped to the block), so a
  // difference one voxel across a block face would read the wrong field: refused, not approximated.
  if (s.shading.enabled && s.adaptive_tolerance > 0.0)
    throw InputError("scene keys 'render.shading' and 'adaptive.tolerance': gradient shading is not "
                     "available with adaptive sampling; set render.shading: false or "
                     "adaptive.tolerance: 0");
  s.adaptive_steps = r.as<std::string>("adaptive.steps");
  if (s.adaptive_steps != "own" && s.adaptive_steps != "fine")
    throw InputError("scene key 'adaptive.steps': expected own or fine, got '" + s.adaptive_steps + "'");
  s.reference_step = r.as<double>("reference.step");
  if (!(s.reference_step > 0.0 && s.reference_step <= 1.0))
    throw InputError("scene key 'reference.step': must be in (0, 1] voxels");
  s.reference_field = r.as<std::string>("reference.field");
  if (s.reference_field != "original" && s.reference_field != "adaptive")
    throw InputError("scene key 'reference.field': expected original or adaptive, got '" +
                     s.reference_field + "'");
  return s;
}

}  // namespace sortlast
