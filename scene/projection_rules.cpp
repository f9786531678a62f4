// render.blend's projections (mip, minip, average, additive) against the rest of the scene: what
// the renderers and compositors do not do with them is refused by name (docs/volumes.md).
#include <string>

#include "scene/scene_reader.h"

namespace sortlast {

void checkProjectionKeys(const Scene& s) {
  const std::string mode(nameOf(s.render.blend));
  if (s.render.mip_exact && s.render.blend != VolumeBlend::kMip && s.render.blend != VolumeBlend::kMinip)
    throw InputError("scene key 'render.mip_exact': only with render.blend: mip or minip (got " + mode + ")");
  if (s.render.mip_exact && !s.render.raycast())
    throw InputError("scene keys 'render.mip_exact' and 'render.method: slicing' cannot go together: "
                     "the exact extremum walks each ray's cells, which only the ray caster follows "
                     "(render.method: raycast); slicing takes the samples on its slice planes");
  if (!s.render.projection()) return;
  auto refuse = [&](const std::string& key, const std::string& why) {
    throw InputError("scene keys 'render.blend: " + mode + "' and '" + key + "' cannot go together: " + why);
  };
  if (s.compositing.precision == Precision::kRgba8)
    refuse("compositing.precision: rgba8",
           "a projection's partial results are values, sums and counts, not colours; 8-bit "
           "colour has no meaning for them (compositing.precision: float)");
  if (s.glow.enabled()) refuse("glow.emitters", "glow is integrated in emission-absorption only");
  if (s.render.shading.enabled)
    refuse("render.shading", "a projection colours one value per pixel, which has no gradient");
  if (s.adaptive.tolerance > 0.0)
    refuse("adaptive.tolerance", "the adaptive blocks are drawn in emission-absorption only");
  if (s.render.adaptive_step)
    refuse("render.adaptive_step", "a projection takes every lattice sample (its result is not an "
                                   "integral that coarser steps approximate)");
}

}  // namespace sortlast
