// The glow section's keys: glow emitters (docs/glow.md).
#include "scene/key_rows.h"
#include "scene/scene_reader.h"
#include <algorithm>
#include <cmath>

std::vector<sortlast::SceneKey> sortlast::glowKeys() {
  const Check kLength = lengthCheck();
  const Check kCoordinate = coordinateCheck();
  return {
    {"glow.emitters", "[]",
     "Energy-wave glow emitters (docs/glow.md): a list of maps `{center: [x, y, z], direction: "
     "[x, y, z], a, b, color: [r, g, b]}`. Each adds the field b / sqrt(dist(P, axis)^2 + eps^2) on "
     "the side of the plane through `center` that `direction` points to (the axis: the line "
     "through `center` along `direction`) and a / sqrt(|P - center|^2 + eps^2) on the other side, "
     "eps = `glow.core_radius`; a = b makes it continuous. `direction` (default [1, 0, 0]) must "
     "not be zero; a and b (default 1) must be >= 0; color entries (default [1, 1, 1]) in [0, 1]. "
     "Per frame of an orbit and per step of a series (`time.step` s with an orbit of N frames "
     "starts at frame s N; without an orbit at frame s), optional linear rates: `velocity` [x, y, z] "
     "added to the centre, `turn` [x, y, z] added to the direction (then normalised), `a_rate`, "
     "`b_rate` added to a and b (refused if a, b would turn negative or the direction zero by the "
     "last frame of the last step). Glow "
     "is emission without opacity, integrated exactly along each ray inside `glow.box`, dimmed "
     "by the volume in front of it and stopped at opaque surfaces. Drawn by `sortlast render`, "
     "`serve` and `reference`; refused with `render.method: slicing`, `adaptive.tolerance` > 0, "
     "`compositing.precision: rgba8` and in situ (docs/glow.md).",
     Structured{"list of emitters"}},
    {"glow.core_radius", "0.01",
     "eps, the emitters' core radius (world units): it keeps the field finite at the "
     "centre and on the axis, where with eps = 0 the integral along a ray through them diverges.",
     Real{member<&Scene::glow, &GlowSpec::core_radius>, {kLength}}},
    {"glow.intensity", "1",
     "Glow radiance per unit of integrated field (times each emitter's color).",
     Real{member<&Scene::glow, &GlowSpec::intensity>, {{"in [0, 1e30]"}}}},
    {"glow.tone_map", "none",
     "`none` (radiance clamped to [0, 1] when written) or `exponential`: 1 - exp(-glow.exposure "
     "x radiance) per channel. Applied once to the final composited frame (volume included: "
     "after compositing, glow and volume light are one sum), never per brick: the map is not "
     "additive, so per-brick mapping would change with the decomposition.",
     Choice{member<&Scene::glow, &GlowSpec::tone_map>}},
    {"glow.exposure", "1", "k of the exponential tone map.",
     Real{member<&Scene::glow, &GlowSpec::exposure>, {{"in (0, 1e30]"}}}},
    {"glow.box", "auto",
     "`[[x0, y0, z0], [x1, y1, z1]]`: the box the glow is integrated in (the field's integral "
     "along an unbounded ray diverges like log length). `auto`: the scene's bounds (volume and "
     "particles); a scene of emitters alone must set it.",
     Structured{"`auto` or [[x0, y0, z0], [x1, y1, z1]]", {kCoordinate}}},
  };
}

namespace sortlast {

// glow.emitters (scene/glow_scene.h has the emitters' own keys) and glow.box. The emitters'
// rates run per frame of an orbit and on through the steps of a series.
void readGlowKeys(const Reader& r, Scene& s) {
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

}  // namespace sortlast
