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
  // mip and minip stop at the first opaque surface, whose colour their partial pixels carry
  // (compositing/projection_pixels.h); a sum and a count (average) or four sums (additive) leave
  // no room in the 8-byte pixel for it.
  if ((s.particles.enabled() || !s.surfaces.empty()) && s.render.blend != VolumeBlend::kMip &&
      s.render.blend != VolumeBlend::kMinip)
    refuse(s.particles.enabled() ? "particles.file / particles.procedural" : "surfaces",
           "only mip and minip are bounded by opaque particles and surfaces (average and additive "
           "partial pixels have no room for the surface's colour); use render.blend: mip or minip");
  // The bounded partial pixels are the ray caster's (it stops each ray at the surface's depth);
  // the slices are blended order-free into one value per pixel, with no depth to stop at.
  if ((s.particles.enabled() || !s.surfaces.empty()) && !s.render.raycast())
    refuse("render.method: slicing",
           "with particles or surfaces a projection stops at the first opaque hit, which only the ray "
           "caster does (render.method: raycast)");
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
