#include "insitu/actions.h"

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include "common/build_features.h"
#include "common/error.h"
#include "common/missing_feature.h"
#include "scene/scene.h"
#include "insitu/output_names.h"
#include "common/listen_address.h"

namespace sortlast {

namespace {

// Where a message points: the file, the line (when yaml-cpp knows it), the render (once its name
// is known), and the key. Every check below fails through here, so every message has all four.
struct Where {
  std::string source;
  std::string render;  // empty at the top level; "render 'NAME'", or "renders[i]" before the name

  [[noreturn]] void fail(const YAML::Node& at, const std::string& key,
                         const std::string& what) const {
    std::string msg = source;
    if (at.IsDefined() && at.Mark().line >= 0) msg += ":" + std::to_string(at.Mark().line + 1);
    msg += ": ";
    if (!render.empty()) msg += render + ": ";
    if (!key.empty()) msg += "key '" + key + "': ";
    throw InputError(msg + what);
  }
};

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// Every key of a map must be one we know, and only once: a typo must not silently fall back to a
// default, and yaml-cpp keeps both copies of a repeated key without saying so.
void checkKeys(const YAML::Node& map, const std::vector<std::string>& known,
               const std::string& prefix, const Where& w) {
  std::set<std::string> seen;
  for (auto it = map.begin(); it != map.end(); ++it) {
    if (!it->first.IsScalar()) w.fail(it->first, prefix + "?", "keys must be names");
    const std::string name = it->first.Scalar();
    bool ok = false;
    for (const std::string& k : known) ok = ok || k == name;
    if (!ok) w.fail(it->first, prefix + name, "unknown key (known here: " + joined(known) + ")");
    if (!seen.insert(name).second) w.fail(it->first, prefix + name, "given twice");
  }
}

std::string stringOf(const YAML::Node& n, const std::string& key, const Where& w) {
  if (!n.IsScalar()) w.fail(n, key, "expected a string");
  return n.Scalar();
}

long long integerOf(const YAML::Node& n, const std::string& key, const Where& w) {
  try {
    if (n.IsScalar()) return n.as<long long>();
  } catch (const YAML::Exception&) {
  }
  w.fail(n, key, "expected an integer");
}

double numberOf(const YAML::Node& n, const std::string& key, const Where& w) {
  double v = std::numeric_limits<double>::quiet_NaN();
  try {
    if (n.IsScalar()) v = n.as<double>();
  } catch (const YAML::Exception&) {
  }
  if (!std::isfinite(v)) w.fail(n, key, "expected a finite number");
  return v;
}

bool isSceneKey(const std::string& path) {
  for (const SceneKey& k : sceneKeys())
    if (path == k.path) return true;
  return false;
}

bool isScenePrefix(const std::string& path) {
  for (const SceneKey& k : sceneKeys())
    if (std::string(k.path).rfind(path + ".", 0) == 0) return true;
  return false;
}

// The value as one line of YAML that the scene parser reads back as the same value (strings
// quoted where they must be, lists and maps in flow style).
std::string flowText(const YAML::Node& value) {
  YAML::Emitter e;
  e.SetMapFormat(YAML::Flow);
  e.SetSeqFormat(YAML::Flow);
  e << value;
  return e.c_str();
}

// A resident session renders the simulation's data as it was published: only keys that change
// how a frame is drawn may be set. The step is the one the simulation publishes.
void checkFrameKey(const YAML::Node& at, const std::string& key, const Where& w) {
  if (key.rfind("time.", 0) == 0)
    w.fail(at, "scene." + key,
           "the step is the one the simulation publishes; time.* cannot be set");
  if (!isFrameKey(key))
    w.fail(
        at, "scene." + key,
        "fixed by the simulation's data and decomposition (volume.*, bricks.*, the particles' "
        "data keys, render.backend (the top-level backend: sets it), adaptive.* cannot be set in situ); a render may set camera.*, "
        "image.*, transfer.*, compositing.*, render.method, render.sample_spacing, "
        "render.ert_threshold, render.shading* and the particles' shading keys "
        "(docs/insitu_actions.md)");
}

// The nested `scene:` map as key.path=VALUE overrides; dotted keys (`image.width: 64`) work too.
void flattenScene(const YAML::Node& map, const std::string& prefix, std::set<std::string>& seen,
                  std::vector<std::string>& out, const Where& w) {
  for (auto it = map.begin(); it != map.end(); ++it) {
    if (!it->first.IsScalar()) w.fail(it->first, "scene." + prefix + "?", "keys must be names");
    const std::string full = prefix + it->first.Scalar();
    if (isSceneKey(full)) {
      checkFrameKey(it->first, full, w);
      if (!seen.insert(full).second) w.fail(it->first, "scene." + full, "given twice");
      out.push_back(full + "=" + flowText(it->second));
    } else if (isScenePrefix(full)) {
      if (!it->second.IsMap()) w.fail(it->second, "scene." + full, "must be a map");
      flattenScene(it->second, full + ".", seen, out, w);
    } else {
      w.fail(it->first, "scene." + full,
             "unknown scene key (docs/scene.md and `sortlast keys` list the known keys)");
    }
  }
}

Trigger parseTrigger(const YAML::Node& n, const Where& w) {
  if (!n.IsMap())
    w.fail(n, "trigger", "expected a map such as {every: 10} or {when: energy, crosses: 0.5}");
  checkKeys(n, {"every", "when", "crosses"}, "trigger.", w);
  if (n.size() == 0)
    w.fail(n, "trigger",
           "empty: give every: N, or when: NAME and crosses: VALUE (leave the "
           "trigger out to render every step)");
  Trigger t;
  if (n["every"]) {
    long long every = integerOf(n["every"], "trigger.every", w);
    if (every < 1 || every > std::numeric_limits<int>::max())
      w.fail(n["every"], "trigger.every", "must be an integer >= 1, got " + std::to_string(every));
    t.every = int(every);
  }
  if (n["when"]) {
    t.when = stringOf(n["when"], "trigger.when", w);
    if (t.when.empty()) w.fail(n["when"], "trigger.when", "must name a published quantity");
    if (!n["crosses"])
      w.fail(n["when"], "trigger.when", "needs crosses: VALUE (the value the quantity crosses)");
  }
  if (n["crosses"]) {
    t.crosses = numberOf(n["crosses"], "trigger.crosses", w);
    if (t.when.empty())
      w.fail(n["crosses"], "trigger.crosses", "needs when: NAME (the quantity that crosses it)");
  }
  return t;
}

// Any trigger fires on more than one step (every N repeats, a quantity may cross again), so a name
// without {step} would have each fired step overwrite the previous one's images.
std::string parseOutput(const YAML::Node& n, const Where& w) {
  std::string out = stringOf(n, "output", w);
  if (out.empty()) w.fail(n, "output", "must not be empty (leave it out to write only cinema)");
  const std::string placeholder = kStepPlaceholder;
  if (out.find(placeholder) == std::string::npos)
    w.fail(n, "output",
           "'" + out +
               "' has no {step}: the trigger can fire on many steps, and each would "
               "overwrite the previous step's images");
  std::string rest = out;
  for (size_t at; (at = rest.find(placeholder)) != std::string::npos;)
    rest.erase(at, placeholder.size());
  if (rest.find_first_of("{}") != std::string::npos)
    w.fail(n, "output", "'" + out + "': {step} is the only placeholder");
  std::string ext = std::filesystem::path(outputName(out, 0, 0, 1)).extension().string();
  if (ext != ".png" && ext != ".exr")
    w.fail(n, "output", "'" + out + "' must end in .png or .exr (got '" + ext + "')");
  return out;
}

// A list of angles, or {count: N} evenly spaced (phi over the full circle from 0, theta strictly
// between the poles).
std::vector<double> parseAngles(const YAML::Node& n, const std::string& key, bool is_phi,
                                const Where& w) {
  std::vector<double> v;
  if (n.IsMap()) {
    checkKeys(n, {"count"}, key + ".", w);
    if (!n["count"]) w.fail(n, key, "expected a list of angles or {count: N}");
    long long count = integerOf(n["count"], key + ".count", w);
    if (count < 1 || count > 360) w.fail(n["count"], key + ".count", "must be in [1, 360]");
    for (long long i = 0; i < count; ++i)
      v.push_back(is_phi ? 360.0 * double(i) / double(count)
                         : -90.0 + 180.0 * double(i + 1) / double(count + 1));
    return v;
  }
  if (!n.IsSequence() || n.size() == 0)
    w.fail(n, key, "expected a non-empty list of angles in degrees, or {count: N}");
  for (const auto& e : n) {
    double a = numberOf(e, key, w);
    if (is_phi && !(a >= 0.0 && a < 360.0)) w.fail(e, key, "angles must be in [0, 360) degrees");
    if (!is_phi && !(a > -90.0 && a < 90.0))
      w.fail(e, key, "angles must be in (-90, 90) degrees (the poles have no azimuth)");
    for (double b : v)
      if (a == b) w.fail(e, key, "angle " + e.Scalar() + " is given twice");
    v.push_back(a == 0.0 ? 0.0 : a);  // -0 would name its images "-0_..."
  }
  return v;
}

CinemaSpec parseCinema(const YAML::Node& n, const Where& w) {
  if (!n.IsMap()) w.fail(n, "cinema", "expected a map with directory, phi and theta");
  checkKeys(n, {"directory", "phi", "theta"}, "cinema.", w);
  CinemaSpec c;
  if (!n["directory"]) w.fail(n, "cinema.directory", "required");
  c.directory = stringOf(n["directory"], "cinema.directory", w);
  if (c.directory.empty()) w.fail(n["directory"], "cinema.directory", "must not be empty");
  // Defaults: eight views around the equator.
  c.phi = {0, 45, 90, 135, 180, 225, 270, 315};
  c.theta = {0};
  if (n["phi"]) c.phi = parseAngles(n["phi"], "cinema.phi", true, w);
  if (n["theta"]) c.theta = parseAngles(n["theta"], "cinema.theta", false, w);
  return c;
}

bool validName(const std::string& name) {
  if (name.empty()) return false;
  for (char ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-') return false;
  return true;
}

RenderAction parseRender(const YAML::Node& n, size_t index, const Where& top) {
  Where w{top.source, "renders[" + std::to_string(index) + "]"};
  if (!n.IsMap()) w.fail(n, "", "expected a map with name, output, trigger, scene, cinema");
  // The name first, so that every later message can say which render it is about.
  RenderAction r;
  if (!n["name"]) w.fail(n, "name", "required");
  r.name = stringOf(n["name"], "name", w);
  if (!validName(r.name))
    w.fail(n["name"], "name", "'" + r.name + "' must be letters, digits, _ and - only");
  w.render = "render '" + r.name + "'";
  checkKeys(n, {"name", "output", "trigger", "scene", "cinema"}, "", w);

  if (n["output"]) r.output = parseOutput(n["output"], w);
  if (n["cinema"]) r.cinema = parseCinema(n["cinema"], w);
  if (r.output.empty() && !r.cinema) w.fail(n, "output", "required (unless cinema is given)");
  r.trigger = n["trigger"] ? parseTrigger(n["trigger"], w) : Trigger{1, "", std::nullopt};

  if (n["scene"]) {
    const YAML::Node& s = n["scene"];
    if (!s.IsMap()) w.fail(s, "scene", "expected a map of scene keys");
    std::set<std::string> seen;
    flattenScene(s, "", seen, r.overrides, w);
  }
  // The scene parser checks the values (ranges, types, camera) now, not at the first render.
  Scene scene;
  try {
    scene = parseScene(SceneText{}, r.overrides);
  } catch (const InputError& e) {
    w.fail(n["scene"] ? n["scene"] : n, "scene", e.what());
  }
  if (r.cinema && scene.orbit.frames > 0)
    w.fail(n["cinema"], "cinema",
           "cannot be combined with camera.orbit.frames: the cinema sweep sets the cameras");
  return r;
}

}  // namespace

Actions parseActions(const std::string& yaml_text, const std::string& source_name) {
  const Where w{source_name, ""};
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw InputError(source_name + ": not valid YAML: " + e.what());
  }
  if (!root.IsMap()) w.fail(root, "", "expected a map with renders: (and on_error, serve)");
  checkKeys(root, {"on_error", "serve", "serve_token", "backend", "device", "renders"}, "", w);

  Actions a;
  // A simulation on GPU nodes renders on them: the backend and device of the whole session (not a
  // render's: every render shares the session's GL context).
  if (root["backend"]) {
    const std::string b = stringOf(root["backend"], "backend", w);
    if (b != "osmesa" && b != "egl") w.fail(root["backend"], "backend", "expected osmesa or egl, got '" + b + "'");
    a.session_overrides.push_back("render.backend=" + b);
  }
  if (root["device"]) {
    const std::string d = stringOf(root["device"], "device", w);
    a.session_overrides.push_back("render.device=" + d);
    try {
      parseScene(SceneText{}, a.session_overrides);
    } catch (const InputError& e) {
      w.fail(root["device"], "device", e.what());
    }
  }
  if (root["on_error"]) {
    std::string mode = stringOf(root["on_error"], "on_error", w);
    if (mode != "report" && mode != "abort")
      w.fail(root["on_error"], "on_error", "expected report or abort, got '" + mode + "'");
    a.abort_on_error = mode == "abort";
  }
  if (root["serve_token"]) {
    a.serve_token = stringOf(root["serve_token"], "serve_token", w);
    if (!root["serve"]) w.fail(root["serve_token"], "serve_token", "given without serve");
  }
  if (root["serve"]) {
    a.serve = stringOf(root["serve"], "serve", w);
    if (!build::kService)  // the live view is the service's front end
      w.fail(root["serve"], "serve", missingFeatureMessage(Feature::kService, "the live view"));
    std::string host;
    try {
      host = parseListen(a.serve).first;
    } catch (const InputError&) {
      w.fail(root["serve"], "serve",
             "expected ADDRESS:PORT such as 127.0.0.1:8080 (port in [0, 65535]), got '" + a.serve +
                 "'");
    }
    if (!isDefaultLoopback(host) && a.serve_token.empty())
      w.fail(
          root["serve"], "serve_token",
          "required: " + a.serve + " is not 127.0.0.1, ::1 or localhost, so others may reach it");
  }

  if (!root["renders"]) w.fail(root, "renders", "required: a list of one or more renders");
  const YAML::Node& list = root["renders"];
  if (!list.IsSequence() || list.size() == 0)
    w.fail(list, "renders", "expected a list of one or more renders");
  for (size_t i = 0; i < list.size(); ++i) {
    RenderAction r = parseRender(list[i], i, w);
    const Where rw{source_name, "render '" + r.name + "'"};
    for (const RenderAction& other : a.renders) {
      if (other.name == r.name) rw.fail(list[i]["name"], "name", "another render has this name");
      if (!r.output.empty() && other.output == r.output)
        rw.fail(list[i]["output"], "output",
                "render '" + other.name +
                    "' writes the same files: their images would overwrite "
                    "each other");
      if (r.cinema && other.cinema &&
          std::filesystem::path(r.cinema->directory).lexically_normal() ==
              std::filesystem::path(other.cinema->directory).lexically_normal())
        rw.fail(list[i]["cinema"]["directory"], "cinema.directory",
                "render '" + other.name + "' uses this directory: their info.json would clash");
    }
    a.renders.push_back(std::move(r));
  }
  return a;
}

}  // namespace sortlast
