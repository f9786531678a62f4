// The clip section's keys: where volumes are shown (common/clip.h).
#include <cmath>

#include "scene/key_rows.h"
#include "scene/scene_reader.h"

std::vector<sortlast::SceneKey> sortlast::clipKeys() {
  const Check kCoordinate = coordinateCheck();
  return {
    {"clip.planes", "[]",
     "Clip planes: a list of maps `{normal: [x, y, z], offset: w}`; each keeps the side "
     "normal . x <= offset (world units; the normal need not be unit, must not be zero). Volumes "
     "only: particles, surfaces and glow are not clipped (the glow is seen through the cut as "
     "through empty space). Every renderer cuts each ray's span to "
     "the kept side, and bricks wholly outside are not drawn.",
     Structured{"list of {normal, offset}", {kCoordinate}}},
    {"clip.box", "none",
     "`[[x0, y0, z0], [x1, y1, z1]]`: only the part of the volume inside this box is shown (with "
     "`clip.planes`, inside both). Volumes only, as `clip.planes`.",
     Structured{"`none` or [[x0, y0, z0], [x1, y1, z1]]", {kCoordinate}}},
  };
}

namespace sortlast {

namespace {

glm::dvec3 vec3Of(const YAML::Node& n, const std::string& key, const YAML::Node& at) {
  std::vector<double> v;
  try {
    if (!n || !n.IsSequence()) throw YAML::Exception(n.Mark(), "not a list");
    for (const auto& x : n) v.push_back(x.as<double>());
  } catch (const YAML::Exception&) {
    v.clear();
  }
  if (v.size() != 3) throw InputError("scene key '" + key + "': expected a list of 3 numbers" + where(at));
  for (double x : v) {
    if (!std::isfinite(x)) throw InputError("scene key '" + key + "': values must be finite" + where(at));
    requireTable(key, x, key);
  }
  return {v[0], v[1], v[2]};
}

}  // namespace

void readClipKeys(const Reader& r, Scene& s) {
  ClipRegion& c = s.clip;
  YAML::Node planes = r.get("clip.planes");
  if (!planes.IsNull()) {
    if (!planes.IsSequence())
      throw InputError("scene key 'clip.planes': expected a list of {normal: [x, y, z], offset: w}" + where(planes));
    for (const YAML::Node& p : planes) {
      if (!p.IsMap() || !p["normal"] || !p["offset"] || p.size() != 2)
        throw InputError("scene key 'clip.planes': each plane is a map {normal: [x, y, z], offset: w}" + where(p));
      ClipPlane cp;
      cp.normal = vec3Of(p["normal"], "clip.planes", p);
      if (!(glm::length(cp.normal) >= kMinLength))
        throw InputError("scene key 'clip.planes': a plane's normal must not be zero (its length must "
                         "be at least 1e-12)" + where(p));
      double w = 0.0;
      try {
        w = p["offset"].as<double>();
      } catch (const YAML::Exception&) {
        throw InputError("scene key 'clip.planes': a plane's offset must be a number" + where(p));
      }
      if (!std::isfinite(w)) throw InputError("scene key 'clip.planes': a plane's offset must be finite" + where(p));
      requireTable("clip.planes", w, "clip.planes");
      cp.offset = w;
      c.planes.push_back(cp);
    }
  }
  YAML::Node box = r.get("clip.box");
  if (!box.IsNull() && !(box.IsScalar() && box.Scalar() == "none")) {
    if (!box.IsSequence() || box.size() != 2)
      throw InputError("scene key 'clip.box': expected none or [[x0, y0, z0], [x1, y1, z1]]" + where(box));
    c.box = {vec3Of(box[0], "clip.box", box), vec3Of(box[1], "clip.box", box)};
    for (int a = 0; a < 3; ++a)
      if (!(c.box.hi[a] - c.box.lo[a] >= kMinLength))
        throw InputError("scene key 'clip.box': the box is empty: it needs lo < hi on every axis (by "
                         "at least 1e-12)" + where(box));
    c.has_box = true;
  }
  if (int(c.halfSpaces().size()) > kMaxClipHalfSpaces)
    throw InputError("scene key 'clip.planes': " + std::to_string(c.planes.size()) +
                     " planes; at most " + std::to_string(kMaxClipHalfSpaces - (c.has_box ? 6 : 0)) +
                     " (the box counts as 6 of " + std::to_string(kMaxClipHalfSpaces) + ")");
}

}  // namespace sortlast
