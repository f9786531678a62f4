#include "scene/isosurface_scene.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "common/error.h"
#include "scene/scene.h"
#include "scene/scene_reader.h"

namespace sortlast {

namespace {

std::string isovalueName(size_t i) { return "render.isovalues[" + std::to_string(i) + "]"; }

double number(const YAML::Node& n, const std::string& name) {
  double v;
  try {
    if (!n.IsScalar()) throw YAML::Exception(n.Mark(), "not a scalar");
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    throw InputError("scene key '" + name + "': expected a number" + where(n));
  }
  if (!std::isfinite(v)) throw InputError("scene key '" + name + "': must be finite" + where(n));
  return v;
}

}  // namespace

std::vector<Isovalue> parseIsovalues(const YAML::Node& list) {
  std::vector<Isovalue> out;
  if (list.IsNull()) return out;
  if (!list.IsSequence())
    throw InputError("scene key 'render.isovalues': expected a list of {value, color: [r, g, b], "
                     "opacity}" + where(list));
  if (list.size() > size_t(kMaxIsovalues))
    throw InputError("scene key 'render.isovalues': at most " + std::to_string(kMaxIsovalues) +
                     " isovalues, got " + std::to_string(list.size()));
  static const std::set<std::string> known = {"value", "color", "opacity"};
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node e = list[i];
    const std::string name = isovalueName(i);
    if (!e.IsMap())
      throw InputError("scene key '" + name + "': expected a map {value, color: [r, g, b], opacity}" + where(e));
    for (auto it = e.begin(); it != e.end(); ++it) {
      const std::string k = it->first.as<std::string>();
      if (!known.count(k))
        throw InputError("scene key '" + name + "': unknown key '" + k + "' (known: value, color, opacity)" +
                         where(it->first));
    }
    Isovalue iso;
    if (!e["value"]) throw InputError("scene key '" + name + ".value': missing (each isovalue needs one)" + where(e));
    iso.value = number(e["value"], name + ".value");
    // Samples are floats on the GPU: the isovalue is compared with float values.
    if (std::abs(iso.value) > 3e38)
      throw InputError("scene key '" + name + ".value': must be within the float range");
    if (e["color"]) {
      const YAML::Node c = e["color"];
      if (!c.IsSequence() || c.size() != 3)
        throw InputError("scene key '" + name + ".color': expected [r, g, b]" + where(c));
      for (int k = 0; k < 3; ++k) {
        iso.colour[k] = number(c[k], name + ".color");
        if (iso.colour[k] < 0.0 || iso.colour[k] > 1.0)
          throw InputError("scene key '" + name + ".color': entries must be in [0, 1], got " +
                           numText(iso.colour[k]) + where(c));
      }
    }
    if (e["opacity"]) {
      iso.opacity = number(e["opacity"], name + ".opacity");
      if (iso.opacity < 0.0 || iso.opacity > 1.0)
        throw InputError("scene key '" + name + ".opacity': must be in [0, 1], got " + numText(iso.opacity) +
                         where(e["opacity"]));
    }
    out.push_back(iso);
  }
  return out;
}

void applyIsosurfaceRules(const Reader& r, Scene& s) {
  if (s.render.blend != VolumeBlend::kIsosurface) {
    if (!s.render.isovalues.empty())
      throw InputError("scene key 'render.isovalues': isovalues are drawn only with render.blend: "
                       "isosurface (render.blend is " + std::string(nameOf(s.render.blend)) + ")");
    return;
  }
  if (s.render.isovalues.empty())
    throw InputError("scene keys 'render.blend' and 'render.isovalues': render.blend: isosurface "
                     "needs at least one isovalue in render.isovalues");
  if (!s.render.raycast())
    throw InputError("scene keys 'render.blend' and 'render.method': isosurfaces are drawn by the "
                     "ray caster only; set render.method: raycast (slicing cannot do them)");
  if (s.adaptive.tolerance > 0.0)
    throw InputError("scene keys 'render.blend' and 'adaptive.tolerance': isosurfaces are not "
                     "available with adaptive sampling; set adaptive.tolerance: 0");
  if (s.reference.field == ReferenceField::kAdaptive)
    throw InputError("scene keys 'render.blend' and 'reference.field': the isosurface reference is "
                     "of the original samples; set reference.field: original");
  if (s.glow.enabled())
    throw InputError("scene keys 'render.blend' and 'glow.emitters': glow is not drawn with "
                     "isosurfaces; remove the emitters or set render.blend: composite");
  if (s.render.adaptive_step)
    throw InputError("scene keys 'render.blend' and 'render.adaptive_step': isosurfaces take every "
                     "lattice sample; set render.adaptive_step: false");
  // Pre-integration is the composite integral's; an isosurface has no use for it.
  if (r.isAuto("transfer.preintegrated"))
    s.transfer.preintegrated = false;
  else if (s.transfer.preintegrated)
    throw InputError("scene keys 'render.blend' and 'transfer.preintegrated': pre-integration does "
                     "not apply to isosurfaces; set transfer.preintegrated: false");
  // The crossing between the sample before a brick's first one and that first one is found by the
  // brick (render/volume/raycast_isosurface.frag.glsl): the sample before lies up to one step
  // outside the brick, which its one-voxel ghost layer holds while the step is at most 1 voxel.
  if (s.render.sample_spacing_auto) {
    s.render.sample_spacing_auto = false;
    s.render.sample_spacing = 0.5;
  } else if (s.render.sample_spacing > 1.0) {
    throw InputError("scene keys 'render.blend' and 'render.sample_spacing': isosurfaces need "
                     "render.sample_spacing <= 1 voxel (the sample before a brick's first lies in "
                     "its one-voxel ghost layer), got " + numText(s.render.sample_spacing));
  }
}

std::vector<std::string> isovalueRangeWarnings(const std::vector<Isovalue>& isovalues, double lo, double hi) {
  std::vector<std::string> out;
  for (size_t i = 0; i < isovalues.size(); ++i)
    if (isovalues[i].value < lo || isovalues[i].value > hi)
      out.push_back("warning: " + isovalueName(i) + ".value " + numText(isovalues[i].value) +
                    " is outside the data's range [" + numText(lo) + ", " + numText(hi) +
                    "]: that surface does not appear");
  return out;
}

}  // namespace sortlast
