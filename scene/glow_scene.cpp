#include "scene/glow_scene.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "common/error.h"
#include "scene/scene_reader.h"

namespace sortlast {

namespace {

std::string emitterName(size_t i) { return "glow.emitters[" + std::to_string(i) + "]"; }

double number(const YAML::Node& e, const std::string& key, const std::string& name,
              double fallback) {
  if (!e[key]) return fallback;
  double v;
  try {
    v = e[key].as<double>();
  } catch (const YAML::Exception&) {
    throw InputError("scene key '" + name + "." + key + "': expected a number" + where(e[key]));
  }
  if (!std::isfinite(v))
    throw InputError("scene key '" + name + "." + key + "': must be finite" + where(e[key]));
  return v;
}

glm::dvec3 vec3(const YAML::Node& e, const std::string& key, const std::string& name,
                glm::dvec3 fallback) {
  if (!e[key]) return fallback;
  std::vector<double> v;
  try {
    if (!e[key].IsSequence()) throw YAML::Exception(e[key].Mark(), "not a list");
    for (const auto& x : e[key]) v.push_back(x.as<double>());
  } catch (const YAML::Exception&) {
    v.clear();
  }
  if (v.size() != 3)
    throw InputError("scene key '" + name + "." + key + "': expected a list of 3 numbers" +
                     where(e[key]));
  for (double x : v) {
    if (!std::isfinite(x))
      throw InputError("scene key '" + name + "." + key + "': values must be finite" +
                       where(e[key]));
    // Float math on the GPU squares distances (common/box.h's limit).
    if (std::abs(x) > kMaxCoordinate)
      throw InputError("scene key '" + name + "." + key + "': values must be within +-1e18" +
                       where(e[key]));
  }
  return {v[0], v[1], v[2]};
}

}  // namespace

std::vector<GlowEmitterSpec> parseGlowEmitters(const YAML::Node& list, int frames) {
  std::vector<GlowEmitterSpec> out;
  if (list.IsNull()) return out;
  if (!list.IsSequence())
    throw InputError(
        "scene key 'glow.emitters': expected a list of emitters ({center, direction, a, b, "
        "color})" +
        where(list));
  static const std::set<std::string> known = {"center",   "direction", "a",      "b",     "color",
                                              "velocity", "turn",      "a_rate", "b_rate"};
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node e = list[i];
    const std::string name = emitterName(i);
    if (!e.IsMap())
      throw InputError("scene key '" + name + "': expected a map {center, direction, a, b, color}" +
                       where(e));
    for (auto it = e.begin(); it != e.end(); ++it) {
      const std::string k = it->first.as<std::string>();
      if (!known.count(k))
        throw InputError(
            "unknown scene key '" + name + "." + k + "'" + where(it->first) +
            " (an emitter has center, direction, a, b, color, velocity, turn, a_rate, b_rate)");
    }
    if (!e["center"]) throw InputError("scene key '" + name + ".center': required" + where(e));
    GlowEmitterSpec s;
    s.at0.centre = vec3(e, "center", name, {});
    glm::dvec3 d = vec3(e, "direction", name, {1, 0, 0});
    if (!(glm::length(d) >= kMinLength))
      throw InputError("scene key '" + name +
                       ".direction': must not be zero (length at least 1e-12)" +
                       where(e["direction"]));
    s.at0.direction = d;  // as given: normalised per frame (emittersAt), after the turn
    s.at0.a = number(e, "a", name, 1.0);
    s.at0.b = number(e, "b", name, 1.0);
    for (auto [key, v] : {std::pair{"a", s.at0.a}, std::pair{"b", s.at0.b}})
      if (v < 0.0)
        throw InputError("scene key '" + name + "." + key +
                         "': must be >= 0 (a negative emitter would absorb)");
    s.at0.colour = vec3(e, "color", name, {1, 1, 1});
    for (int c = 0; c < 3; ++c)
      if (s.at0.colour[c] < 0.0 || s.at0.colour[c] > 1.0)
        throw InputError("scene key '" + name + ".color': entries must be in [0, 1]");
    s.velocity = vec3(e, "velocity", name, {});
    s.turn = vec3(e, "turn", name, {});
    s.a_rate = number(e, "a_rate", name, 0.0);
    s.b_rate = number(e, "b_rate", name, 0.0);
    out.push_back(s);
  }
  checkGlowRates(out, frames);
  return out;
}

void checkGlowRates(const std::vector<GlowEmitterSpec>& emitters, int frames) {
  const int last = std::max(0, frames - 1);
  for (size_t i = 0; i < emitters.size(); ++i) {
    const GlowEmitterSpec& s = emitters[i];
    const std::string name = emitterName(i);
    // The last frame is where a linear rate goes furthest.
    if (s.at0.a + last * s.a_rate < 0.0 || s.at0.b + last * s.b_rate < 0.0)
      throw InputError("scene keys '" + name +
                       ".a_rate' / '.b_rate': a or b would be negative at frame " +
                       std::to_string(last) + " of " + std::to_string(frames));
    for (int f = 0; f <= last; ++f)
      if (!(glm::length(s.at0.direction + double(f) * s.turn) >= kMinLength))
        throw InputError("scene key '" + name + ".turn': the direction becomes zero at frame " +
                         std::to_string(f));
  }
}

std::vector<GlowEmitter> GlowSpec::emittersAt(int frame) const {
  std::vector<GlowEmitter> out;
  const double f = double(first_frame) + double(frame);
  for (const GlowEmitterSpec& s : emitters) {
    GlowEmitter e = s.at0;
    e.centre += f * s.velocity;
    e.direction = glm::normalize(s.at0.direction + f * s.turn);
    e.a += f * s.a_rate;
    e.b += f * s.b_rate;
    out.push_back(e);
  }
  return out;
}

double toneMap(const GlowSpec& g, double radiance) {
  if (g.tone_map == ToneMap::kExponential) return -std::expm1(-g.exposure * radiance);
  return radiance;
}

}  // namespace sortlast
